// MeshoptDecode: meshopt-compressed buffer views come back (vertices byte for byte, triangles as they were), the views
// then point at the decoded bytes, the fallback buffer goes, and streams Debian's meshoptimizer cannot read are one
// line.
#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/IO/MeshoptDecode.hh>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>

using namespace OpenMeshSkinned;
using namespace OpenMeshSkinned::detail;
using json = nlohmann::json;

namespace {

// As a file's JSON reads: numbers that are not negative are unsigned.
json as_read(const json& j) { return json::parse(j.dump()); }

struct Encoded {
  std::string vertices, indices;  // as decoded
  std::string bin;                // buffer 0: both streams compressed
  json doc;
};

// Twelve float3 vertices and a triangle list over them, compressed into buffer 0 with a fallback buffer
// 1 that the views stand on; \p ext names the extension.
Encoded encoded(const char* ext) {
  Encoded e;
  std::vector<float> v;
  for (int i = 0; i < 12; ++i) v.insert(v.end(), {float(i), float(i * i) * 0.25f, -float(i)});
  std::vector<unsigned int> idx;
  for (unsigned int i = 0; i + 2 < 12; ++i) idx.insert(idx.end(), {i, i + 1, i + 2});
  e.vertices.assign(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
  e.indices.assign(reinterpret_cast<const char*>(idx.data()), idx.size() * sizeof(unsigned int));

  std::vector<unsigned char> vb(meshopt_encodeVertexBufferBound(12, 12));
  vb.resize(meshopt_encodeVertexBuffer(vb.data(), vb.size(), v.data(), 12, 12));
  std::vector<unsigned char> ib(meshopt_encodeIndexBufferBound(idx.size(), 12));
  ib.resize(meshopt_encodeIndexBuffer(ib.data(), ib.size(), idx.data(), idx.size()));
  e.bin.assign(vb.begin(), vb.end());
  while (e.bin.size() % 4) e.bin += '\0';
  const size_t ib_offset = e.bin.size();
  e.bin.append(ib.begin(), ib.end());

  const size_t fallback = e.vertices.size() + e.indices.size();
  e.doc["buffers"] = {{{"byteLength", e.bin.size()}},
                      {{"byteLength", fallback}, {"extensions", {{ext, {{"fallback", true}}}}}}};
  e.doc["bufferViews"] = {
      {{"buffer", 1},
       {"byteLength", e.vertices.size()},
       {"byteStride", 12},
       {"extensions",
        {{ext,
          {{"buffer", 0}, {"byteLength", vb.size()}, {"byteStride", 12}, {"count", 12}, {"mode", "ATTRIBUTES"}}}}}},
      {{"buffer", 1},
       {"byteOffset", e.vertices.size()},
       {"byteLength", e.indices.size()},
       {"extensions",
        {{ext,
          {{"buffer", 0},
           {"byteOffset", ib_offset},
           {"byteLength", ib.size()},
           {"byteStride", 4},
           {"count", idx.size()},
           {"mode", "TRIANGLES"}}}}}}};
  e.doc = as_read(e.doc);
  return e;
}

// The triangles of an index buffer, each rotated to start at its smallest index: the index codec may
// rotate a triangle, keeping its winding.
std::vector<std::array<uint32_t, 3>> triangles(const std::string& indices) {
  std::vector<std::array<uint32_t, 3>> out(indices.size() / 12);
  std::memcpy(out.data(), indices.data(), out.size() * 12);
  for (auto& t : out) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return out;
}

std::string error_of(Encoded& e) {
  GltfBytes bytes(e.doc, &e.bin, ".", "t.glb");
  try {
    decode_meshopt(e.doc, bytes, "t.glb");
  } catch (const IOError& x) {
    return x.what();
  }
  return "";
}

}  // namespace

TEST(MeshoptDecode, ViewsComeBackAsEncoded) {
  for (const char* ext : kMeshoptExtensions) {
    Encoded e = encoded(ext);
    GltfBytes bytes(e.doc, &e.bin, ".", "t.glb");
    ASSERT_TRUE(decode_meshopt(e.doc, bytes, "t.glb")) << ext;
    ASSERT_EQ(e.doc["bufferViews"].size(), 2u) << "the decoded bytes take the compressed views' places";
    for (const auto& view : e.doc["bufferViews"]) {
      EXPECT_FALSE(view.contains("extensions"));
      EXPECT_EQ(view["buffer"], 0);
      EXPECT_EQ(view["byteOffset"].get<size_t>() % 4, 0u);
    }
    EXPECT_EQ(e.doc["bufferViews"][0]["byteStride"], 12);
    EXPECT_EQ(bytes.view_bytes(0), e.vertices) << ext;
    EXPECT_EQ(triangles(bytes.view_bytes(1)), triangles(e.indices)) << ext;
    EXPECT_TRUE(bytes.added().empty()) << "a GLB's decoded data goes into its binary chunk";

    drop_fallback_buffers(e.doc);
    ASSERT_EQ(e.doc["buffers"].size(), 1u);
    EXPECT_EQ(e.doc["buffers"][0]["byteLength"], e.bin.size());
  }
}

TEST(MeshoptDecode, NothingCompressedIsNoChange) {
  json doc = {{"buffers", json::array({{{"byteLength", 4}}})},
              {"bufferViews", json::array({{{"buffer", 0}, {"byteLength", 4}}})}};
  doc = as_read(doc);
  const json before = doc;
  std::string bin(4, '\0');
  GltfBytes bytes(doc, &bin, ".", "t.glb");
  EXPECT_FALSE(decode_meshopt(doc, bytes, "t.glb"));
  EXPECT_EQ(doc, before);
}

TEST(MeshoptDecode, UndecodableStreamsAreOneLine) {
  {
    Encoded e = encoded(kMeshoptExtensions[0]);
    e.bin[0] = char(0xa1);  // vertex codec version 1, which meshoptimizer 0.18 predates
    EXPECT_NE(error_of(e).find("t.glb: buffer view 0 (EXT_meshopt_compression) uses meshopt vertex codec version 1"),
              std::string::npos)
        << error_of(e);
  }
  {
    Encoded e = encoded(kMeshoptExtensions[0]);
    e.doc["bufferViews"][0]["byteLength"] = 100;
    EXPECT_EQ(error_of(e),
              "t.glb: buffer view 0 (EXT_meshopt_compression) decodes to 12 x 12 bytes, not the view's "
              "byteLength");
  }
  {
    Encoded e = encoded(kMeshoptExtensions[1]);
    e.doc["bufferViews"][1]["extensions"][kMeshoptExtensions[1]]["byteLength"] = 1 << 20;
    EXPECT_EQ(error_of(e), "t.glb: buffer view 1 (KHR_meshopt_compression) runs past its buffer");
  }
  {
    Encoded e = encoded(kMeshoptExtensions[1]);
    e.doc["bufferViews"][0]["extensions"][kMeshoptExtensions[1]]["filter"] = "COLOR";
    EXPECT_EQ(error_of(e),
              "t.glb: buffer view 0 (KHR_meshopt_compression) uses the filter COLOR, which Debian's meshoptimizer "
              "cannot decode");
  }
  {
    Encoded e = encoded(kMeshoptExtensions[0]);
    e.bin[e.doc["bufferViews"][1]["extensions"][kMeshoptExtensions[0]]["byteOffset"].get<size_t>()] = char(0x7f);
    EXPECT_NE(error_of(e).find("cannot be decoded (meshoptimizer"), std::string::npos) << error_of(e);
  }
}
