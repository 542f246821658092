// The exporter numbers UV sets from 0 without gaps: every texture reference's texCoord (core, extensions,
// KHR_texture_transform's override) follows its set to its new number, and the tangents of a normal map
// follow the normal map's set (IO/ExportMaterials.cc, IO/ExportMesh.cc).
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Textures.hh>
#include <OpenMeshSkinned/Mesh/CornerAttributes.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/Morph.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace OpenMeshSkinned;

namespace {

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A skinned tube along +y (Procedural.hh) with UV set 0 = (angle / 2 pi, y / 2) and UV set 2 = (y / 2,
// angle / 2 pi) but no set 1 (a gap: the isolated reader's archive and other formats' readers can leave
// one), and a material whose every texture reference but one reads set 2: base colour, normal map, a
// clear-coat texture, occlusion through KHR_texture_transform's override; the emissive map names set 5,
// which nothing has.
SkinnedMesh gap_tube() {
  TubeOptions opt;
  opt.around = 16;
  opt.along = 8;
  SkinnedMesh mesh = make_skinned_tube(opt, 30.0);
  const CornerChannel set2 = add_corner_channel(mesh, CornerKind::TexCoord, 2);
  for (auto heh : mesh.halfedges()) {
    if (mesh.is_boundary(heh)) continue;
    const auto p = mesh.point(mesh.to_vertex_handle(heh));
    // The angle from the face's centre, so that the seam at angle pi splits cleanly.
    const auto c = mesh.calc_face_centroid(mesh.face_handle(heh));
    double a = std::atan2(p[2], p[0]);
    if (std::atan2(c[2], c[0]) < 0 && a > M_PI / 2) a -= 2 * M_PI;
    if (std::atan2(c[2], c[0]) > 0 && a < -M_PI / 2) a += 2 * M_PI;
    const float u = float((a + M_PI) / (2 * M_PI)), v = float(p[1] / 2);
    mesh.set_texcoord2D(heh, SkinnedMesh::TexCoord2D(u, v));
    mesh.property(set2.handle, heh) = OpenMesh::Vec4f(v, u, 0, 0);
  }
  Material& m = materials(mesh).at(0);
  m.gltf = R"({
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 2}},
    "normalTexture": {"index": 0, "texCoord": 2, "scale": 0.5},
    "occlusionTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 2, "scale": [2, 2]}}},
    "emissiveTexture": {"index": 0, "texCoord": 5},
    "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatTexture": {"index": 0, "texCoord": 2}}}
  })";
  Texture t;
  t.gltf = R"({"source": 0})";
  auto img = std::make_shared<Image>();
  std::vector<unsigned char> px(4 * 4 * 4, 200);
  EXPECT_TRUE(encode_rgba_png(px.data(), 4, 4, "grey.png", *img));
  t.images.push_back(img);
  m.textures = {t};
  return mesh;
}

json load_glb_json(const fs::path& p) {
  const std::string data = read_file(p);
  uint32_t len = 0;
  std::memcpy(&len, data.data() + 12, 4);
  return json::parse(data.substr(20, len));
}

// The elements of a float accessor of a GLB as written by the exporter (one view each, tightly packed).
std::vector<float> floats(const fs::path& glb, const json& j, int accessor) {
  const std::string data = read_file(glb);
  uint32_t len = 0;
  std::memcpy(&len, data.data() + 12, 4);
  const std::string bin = data.substr(28 + len);
  const json& a = j["accessors"][accessor];
  const json& v = j["bufferViews"][a["bufferView"].get<int>()];
  const size_t k = a["type"] == "VEC2" ? 2 : a["type"] == "VEC3" ? 3 : 4;
  std::vector<float> out(k * a["count"].get<size_t>());
  std::memcpy(out.data(), bin.data() + v.value("byteOffset", 0) + a.value("byteOffset", 0), out.size() * 4);
  return out;
}

}  // namespace

TEST(ExportUvSets, EveryTexCoordFollowsItsSetToItsNewNumber) {
  const fs::path dir = omsk_test::scratch_dir("export_uv_sets", "gap");
  const SkinnedMesh mesh = gap_tube();
  const fs::path out = dir / "gap.glb";
  export_gltf(mesh, out.string());
  const auto v = omsk_test::run_validator(out.string());
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_EQ(v.output.find("TEXCOORD"), std::string::npos) << v.output;
  EXPECT_EQ(v.output.find("TANGENT_SPACE"), std::string::npos) << v.output;
  const json j = load_glb_json(out);
  const json& m = j["materials"][0];
  EXPECT_EQ(m["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"], 1);
  EXPECT_EQ(m["normalTexture"]["texCoord"], 1);
  EXPECT_EQ(m["extensions"]["KHR_materials_clearcoat"]["clearcoatTexture"]["texCoord"], 1);
  EXPECT_EQ(m["occlusionTexture"].value("texCoord", 0), 0) << "its own set stays 0";
  EXPECT_EQ(m["occlusionTexture"]["extensions"]["KHR_texture_transform"]["texCoord"], 1);
  ASSERT_TRUE(m.contains("emissiveTexture"));
  EXPECT_EQ(m["emissiveTexture"].value("texCoord", 0), 0) << "a set nothing has reads TEXCOORD_0 (0 is not written)";
  const json& attr = j["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_TRUE(attr.contains("TEXCOORD_0") && attr.contains("TEXCOORD_1"));
  EXPECT_FALSE(attr.contains("TEXCOORD_2"));
  const std::vector<float> pos = floats(out, j, attr["POSITION"]), uv0 = floats(out, j, attr["TEXCOORD_0"]),
                           uv1 = floats(out, j, attr["TEXCOORD_1"]), tan = floats(out, j, attr["TANGENT"]),
                           nrm = floats(out, j, attr["NORMAL"]);
  ASSERT_EQ(uv1.size() / 2, pos.size() / 3);
  ASSERT_EQ(tan.size() / 4, pos.size() / 3);
  for (size_t i = 0; i < pos.size() / 3; ++i) {
    // TEXCOORD_1 is the input's set 2: set 0 with u and v swapped (and glTF's v = 1 - v for both).
    EXPECT_NEAR(uv1[2 * i], 1.0f - uv0[2 * i + 1], 1e-6) << i;
    EXPECT_NEAR(1.0f - uv1[2 * i + 1], uv0[2 * i], 1e-6) << i;
    // The normal map reads set 2, whose u grows along the tube (+y; set 0's u goes around it).
    EXPECT_GT(tan[4 * i + 1], 0.99) << i;
    EXPECT_NEAR(tan[4 * i] * nrm[3 * i] + tan[4 * i + 1] * nrm[3 * i + 1] + tan[4 * i + 2] * nrm[3 * i + 2], 0.0, 1e-5);
    EXPECT_EQ(std::abs(tan[4 * i + 3]), 1.0f);
  }
}

TEST(ExportUvSets, TangentsBesideMorphNormalOffsetsStayValid) {
  // A bulge with normal offsets on a normal-mapped tube: the LOD's TANGENT and the target's NORMAL
  // offsets (no TANGENT offsets, which glTF lets a target omit) validate together.
  SkinnedMesh mesh = gap_tube();
  const auto h = add_morph_targets(mesh);
  MorphTarget bulge;
  bulge.name = "bulge";
  bulge.normals = true;
  morph_targets(mesh).push_back(bulge);
  for (auto vh : mesh.vertices()) {
    const auto p = mesh.point(vh);
    const float s = float(0.1 * std::sin(M_PI * p[1] / 2.0));
    mesh.property(h, vh) = {Eigen::Vector3f(s * p[0], 0.0f, s * p[2])};
  }
  const fs::path out = omsk_test::scratch_dir("export_uv_sets", "morph") / "bulge.glb";
  export_gltf(mesh, out.string());
  const auto v = omsk_test::run_validator(out.string());
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_EQ(v.output.find("TANGENT"), std::string::npos) << v.output;
  const json j = load_glb_json(out);
  const json& prim = j["meshes"][0]["primitives"][0];
  EXPECT_TRUE(prim["attributes"].contains("TANGENT"));
  ASSERT_EQ(prim["targets"].size(), 1u);
  EXPECT_TRUE(prim["targets"][0].contains("NORMAL"));
  EXPECT_FALSE(prim["targets"][0].contains("TANGENT"));
}
