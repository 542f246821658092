// DracoDecode: a Draco primitive comes back as the triangles it was made from, in the component types its
// accessors declare and with their bounds made the decoded values'; two primitives sharing an accessor
// get one each, and data that cannot be decoded is one line naming the primitive.
#include <OpenMeshSkinned/IO/DracoDecode.hh>
#include <OpenMeshSkinned/IO/GltfAccessors.hh>
#include <OpenMeshSkinned/IO/IOError.hh>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

using namespace OpenMeshSkinned;
using namespace OpenMeshSkinned::detail;
using json = nlohmann::json;

namespace {

// A unit square in two triangles (corners numbered 0..3), with a joint index per corner.
const float kCorners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, 0.5f}};
const std::array<int, 3> kTriangles[2] = {{0, 1, 2}, {0, 2, 3}};

// As a file's JSON reads: numbers that are not negative are unsigned.
json as_read(const json& j) { return json::parse(j.dump()); }

struct Fixture {
  std::string bin;
  json doc;
};

// Both primitives of one mesh read the same Draco data and share their POSITION accessor; the first has
// an indices accessor, the second none.
Fixture fixture() {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(2);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int joints = builder.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT16);
  for (int f = 0; f < 2; ++f) {
    const auto& t = kTriangles[f];
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), kCorners[t[0]], kCorners[t[1]], kCorners[t[2]]);
    uint16_t j[3][4];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 4; ++k) j[c][k] = uint16_t(k == 0 ? 10 * t[c] + 1 : 0);
    builder.SetAttributeValuesForFace(joints, draco::FaceIndex(f), j[0], j[1], j[2]);
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 6);
  draco::EncoderBuffer out;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());

  Fixture f;
  f.bin.assign(out.data(), out.size());
  const json ext = {
      {"KHR_draco_mesh_compression",
       {{"bufferView", 0},
        {"attributes",
         {{"POSITION", mesh->attribute(pos)->unique_id()}, {"JOINTS_0", mesh->attribute(joints)->unique_id()}}}}}};
  f.doc["buffers"] = {{{"byteLength", f.bin.size()}}};
  f.doc["bufferViews"] = {{{"buffer", 0}, {"byteLength", f.bin.size()}}};
  f.doc["accessors"] = {
      {{"componentType", kFloat}, {"type", "VEC3"}, {"count", 4}, {"min", {0, 0, 0}}, {"max", {1, 1, 0.5}}},
      {{"componentType", kUnsignedShort}, {"type", "SCALAR"}, {"count", 6}},
      {{"componentType", kUnsignedByte}, {"type", "VEC4"}, {"count", 4}}};
  f.doc["meshes"] = {{{"primitives",
                       {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 2}}}, {"indices", 1}, {"extensions", ext}},
                        {{"attributes", {{"POSITION", 0}, {"JOINTS_0", 2}}}, {"extensions", ext}}}}}};
  f.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  f.doc = as_read(f.doc);
  return f;
}

std::string error_of(Fixture& f) {
  GltfBytes bytes(f.doc, &f.bin, ".", "t.glb");
  try {
    decode_draco(f.doc, bytes, "t.glb");
  } catch (const IOError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DracoDecode, PrimitivesComeBackAsTheirTriangles) {
  Fixture f = fixture();
  GltfBytes bytes(f.doc, &f.bin, ".", "t.glb");
  ASSERT_TRUE(decode_draco(f.doc, bytes, "t.glb"));
  const json& prims = f.doc["meshes"][0]["primitives"];
  std::set<size_t> used;
  for (const json& prim : prims) {
    EXPECT_FALSE(prim.contains("extensions"));
    const size_t ia = prim["indices"].get<size_t>(), pa = prim["attributes"]["POSITION"].get<size_t>(),
                 ja = prim["attributes"]["JOINTS_0"].get<size_t>();
    EXPECT_TRUE(used.insert(ia).second && used.insert(pa).second && used.insert(ja).second)
        << "every primitive writes accessors of its own";
    const json& ind = f.doc["accessors"][ia];
    EXPECT_EQ(ind["componentType"], kUnsignedInt);
    EXPECT_EQ(ind["count"], 6);
    EXPECT_EQ(f.doc["accessors"][ja]["componentType"], kUnsignedByte) << "the accessor's own type";

    const std::vector<double> idx = accessor_values(f.doc, ia, bytes, "t.glb");
    const std::vector<double> p = accessor_values(f.doc, pa, bytes, "t.glb");
    const std::vector<double> j = accessor_values(f.doc, ja, bytes, "t.glb");
    const size_t points = f.doc["accessors"][pa]["count"].get<size_t>();
    ASSERT_EQ(p.size(), 3 * points);
    ASSERT_EQ(j.size(), 4 * points);
    // Each decoded point is a corner of the square, within 6-bit quantisation, with that corner's joint.
    std::vector<int> corner(points, -1);
    for (size_t v = 0; v < points; ++v)
      for (int c = 0; c < 4; ++c)
        if (std::abs(p[3 * v] - kCorners[c][0]) + std::abs(p[3 * v + 1] - kCorners[c][1]) +
                std::abs(p[3 * v + 2] - kCorners[c][2]) <
            0.05) {
          corner[v] = c;
          EXPECT_EQ(j[4 * v], 10 * c + 1);
        }
    std::set<std::array<int, 3>> got, want;
    for (size_t t = 0; t < 2; ++t) {
      std::array<int, 3> tri;
      for (int c = 0; c < 3; ++c) tri[c] = corner[size_t(idx[3 * t + c])];
      std::sort(tri.begin(), tri.end());
      got.insert(tri);
      std::array<int, 3> w = kTriangles[t];
      std::sort(w.begin(), w.end());
      want.insert(w);
    }
    EXPECT_EQ(got, want);
    // The bounds are the decoded values' (Draco quantises: the file's are the original's).
    for (int c = 0; c < 3; ++c) {
      double lo = INFINITY, hi = -INFINITY;
      for (size_t v = 0; v < points; ++v) lo = std::min(lo, p[3 * v + c]), hi = std::max(hi, p[3 * v + c]);
      EXPECT_EQ(f.doc["accessors"][pa]["min"][c].get<double>(), lo);
      EXPECT_EQ(f.doc["accessors"][pa]["max"][c].get<double>(), hi);
    }
  }
}

TEST(DracoDecode, UndecodableDataIsOneLine) {
  {
    Fixture f = fixture();
    for (size_t i = 0; i < f.bin.size(); ++i) f.bin[i] = char(0x5a);
    EXPECT_EQ(error_of(f).rfind("t.glb: primitive 0 of mesh 0: its Draco data cannot be decoded: ", 0), 0u)
        << error_of(f);
  }
  {
    Fixture f = fixture();
    f.doc["meshes"][0]["primitives"][1]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = 7u;
    EXPECT_EQ(error_of(f), "t.glb: primitive 1 of mesh 0: its Draco data has no attribute 7 (POSITION)");
  }
  {
    Fixture f = fixture();
    f.doc["meshes"][0]["primitives"][0]["mode"] = 1;
    EXPECT_EQ(error_of(f), "t.glb: primitive 0 of mesh 0 is Draco-compressed and not made of triangles");
  }
  {
    Fixture f = fixture();
    f.doc["meshes"][0]["primitives"][0]["attributes"].erase("JOINTS_0");
    EXPECT_EQ(error_of(f), "t.glb: primitive 0 of mesh 0: Draco attribute JOINTS_0 has no accessor");
  }
}
