// GltfAccessors: an accessor's values as the glTF spec gives them (normalised integers, byte strides,
// sparse substitutions), refused in one line when they run past their data, and written back as floats.
#include <OpenMeshSkinned/IO/GltfAccessors.hh>
#include <OpenMeshSkinned/IO/IOError.hh>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <limits>

using namespace OpenMeshSkinned;
using namespace OpenMeshSkinned::detail;
using json = nlohmann::json;

namespace {

template <typename T>
void put(std::string& bin, T v) {
  bin.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// As a file's JSON reads: numbers that are not negative are unsigned.
json as_read(const json& j) { return json::parse(j.dump()); }

// A GLB-like document: buffer 0 is \p bin, one view over all of it with \p stride.
json doc_over(const std::string& bin, size_t stride = 0) {
  json view = {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bin.size()}};
  if (stride) view["byteStride"] = stride;
  return {{"buffers", json::array({{{"byteLength", bin.size()}}})}, {"bufferViews", json::array({view})}};
}

float float_at(const std::string& data, size_t i) {
  float f;
  std::memcpy(&f, data.data() + i * sizeof f, sizeof f);
  return f;
}

}  // namespace

TEST(GltfAccessors, NormalisedIntegersReadAsTheSpecMapsThem) {
  std::string bin;
  put<int16_t>(bin, -32768), put<int16_t>(bin, 32767), put<int16_t>(bin, 0), put<int16_t>(bin, 16384);
  json doc = doc_over(bin);
  doc["accessors"] = {
      {{"bufferView", 0}, {"componentType", kShort}, {"type", "VEC2"}, {"count", 2}, {"normalized", true}}};
  doc = as_read(doc);
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  const std::vector<double> v = accessor_values(doc, 0, bytes, "t.glb");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], -1.0);  // -32768 clamps to -1, as the spec says
  EXPECT_EQ(v[1], 1.0);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_DOUBLE_EQ(v[3], 16384.0 / 32767.0);
  const std::vector<double> stored = accessor_values(doc, 0, bytes, "t.glb", /*as_stored=*/true);
  EXPECT_EQ(stored[0], -32768.0);
  EXPECT_EQ(stored[3], 16384.0);
}

TEST(GltfAccessors, ByteStrideSkipsThePadding) {
  std::string bin;
  for (uint8_t k = 0; k < 3; ++k) put<uint8_t>(bin, 51 * k), put<uint8_t>(bin, 255), put<uint16_t>(bin, 0xffff);
  json doc = doc_over(bin, 4);
  doc["accessors"] = {
      {{"bufferView", 0}, {"componentType", kUnsignedByte}, {"type", "VEC2"}, {"count", 3}, {"normalized", true}}};
  doc = as_read(doc);
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  const std::vector<double> v = accessor_values(doc, 0, bytes, "t.glb");
  ASSERT_EQ(v.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(v[2 * k], 51.0 * k / 255.0);
    EXPECT_EQ(v[2 * k + 1], 1.0);
  }
}

TEST(GltfAccessors, SparseValuesReplaceTheirElements) {
  std::string bin;
  put<uint8_t>(bin, 2), put<uint8_t>(bin, 0), put<uint16_t>(bin, 0);  // indices, padded to 4
  put<float>(bin, 7.0f), put<float>(bin, 8.0f), put<float>(bin, 9.0f);
  put<float>(bin, -1.0f), put<float>(bin, -2.0f), put<float>(bin, -3.0f);
  json doc = doc_over(bin);
  doc["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 2}},
                        {{"buffer", 0}, {"byteOffset", 4}, {"byteLength", 24}}};
  doc["accessors"] = {{{"componentType", kFloat},
                       {"type", "VEC3"},
                       {"count", 3},
                       {"sparse",
                        {{"count", 2},
                         {"indices", {{"bufferView", 0}, {"componentType", kUnsignedByte}}},
                         {"values", {{"bufferView", 1}}}}}}};
  doc = as_read(doc);
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  const std::vector<double> v = accessor_values(doc, 0, bytes, "t.glb");
  EXPECT_EQ(v, (std::vector<double>{-1, -2, -3, 0, 0, 0, 7, 8, 9}));

  doc["accessors"][0]["sparse"]["count"] = 3;  // one more than the views hold
  EXPECT_THROW(
      {
        try {
          accessor_values(doc, 0, bytes, "t.glb");
        } catch (const IOError& e) {
          EXPECT_STREQ(e.what(), "t.glb: accessor 0: its sparse part runs past its buffer views");
          throw;
        }
      },
      IOError);
}

TEST(GltfAccessors, DataPastTheViewIsOneLine) {
  std::string bin(12, '\0');
  json doc = doc_over(bin);
  doc["accessors"] = {{{"bufferView", 0}, {"componentType", kFloat}, {"type", "VEC3"}, {"count", 2}}};
  doc = as_read(doc);
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  try {
    accessor_values(doc, 0, bytes, "t.glb");
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_STREQ(e.what(), "t.glb: accessor 0 runs past its buffer view");
  }
  doc["accessors"][0]["type"] = "VEC5";
  EXPECT_THROW(accessor_values(doc, 0, bytes, "t.glb"), IOError);
}

TEST(GltfAccessors, FitsNeverOverflows) {
  const size_t huge = std::numeric_limits<size_t>::max();
  EXPECT_TRUE(fits(0, 3, 12, 12, 36));
  EXPECT_FALSE(fits(0, 4, 12, 12, 36));
  EXPECT_FALSE(fits(4, 3, 12, 12, 36));
  EXPECT_FALSE(fits(0, huge, huge / 2, 4, 1 << 20));
  EXPECT_TRUE(fits(36, 0, 12, 12, 36));
  EXPECT_FALSE(fits(37, 0, 12, 12, 36));
}

TEST(GltfAccessors, WrittenAsFloatsWithTheirBounds) {
  std::string bin;
  put<uint8_t>(bin, 0), put<uint8_t>(bin, 255), put<uint8_t>(bin, 128), put<uint8_t>(bin, 64);
  json doc = doc_over(bin);
  doc["accessors"] = {{{"bufferView", 0},
                       {"componentType", kUnsignedByte},
                       {"type", "VEC2"},
                       {"count", 2},
                       {"normalized", true},
                       {"byteOffset", 0},
                       {"min", {0, 64}},
                       {"max", {128, 255}}},
                      {{"bufferView", 0}, {"componentType", kUnsignedByte}, {"type", "SCALAR"}, {"count", 4}}};
  doc = as_read(doc);
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  write_float_accessor(doc, 0, accessor_values(doc, 0, bytes, "t.glb"), bytes);
  const json& a = doc["accessors"][0];
  EXPECT_EQ(a["componentType"], kFloat);
  EXPECT_FALSE(a.contains("normalized"));
  EXPECT_FALSE(a.contains("byteOffset"));
  EXPECT_EQ(a["count"], 2);
  EXPECT_EQ(a["min"], json({0.0, double(float(64 / 255.0))}));
  EXPECT_EQ(a["max"], json({double(float(128 / 255.0)), 1.0}));
  const std::string data = bytes.view_bytes(a["bufferView"].get<size_t>());
  ASSERT_EQ(data.size(), 4 * sizeof(float));
  EXPECT_EQ(float_at(data, 1), 1.0f);
  EXPECT_EQ(float_at(data, 2), float(128 / 255.0));

  write_float_accessor(doc, 1, accessor_values(doc, 1, bytes, "t.glb"), bytes);  // no bounds before, none after
  EXPECT_FALSE(doc["accessors"][1].contains("min"));
  EXPECT_EQ(float_at(bytes.view_bytes(doc["accessors"][1]["bufferView"].get<size_t>()), 1), 255.0f);
}
