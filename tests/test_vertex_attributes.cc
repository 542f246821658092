// Every vertex attribute a viewer uses survives decimation: further UV sets, vertex colours (with their
// seams), morph normal offsets (Mesh/CornerAttributes.hh, Collapse/CornerTransferT.hh, IO/ExportMesh.cc).
#include "fixtures.hh"
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportArchive.hh>
#include <OpenMeshSkinned/Mesh/CornerAttributes.hh>
#include <OpenMeshSkinned/Skin/Morph.hh>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {

const std::string morph_cube =
    std::string(OMSK_TEST_MODELS) + "/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";

// A new accessor holding \p accessor's elements twice over (copies i + count of every vertex i).
int doubled(tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor a = m.accessors.at(accessor);
  const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
  const size_t elem = tinygltf::GetComponentSizeInBytes(a.componentType) * tinygltf::GetNumComponentsInType(a.type);
  if (v.byteStride != 0 && size_t(v.byteStride) != elem) throw std::runtime_error("interleaved accessor");
  const unsigned char* src = m.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset;
  const std::vector<unsigned char> once(src, src + elem * a.count);
  auto& bytes = m.buffers.at(0).data;
  while (bytes.size() % 4) bytes.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bytes.size();
  view.byteLength = 2 * once.size();
  view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  bytes.insert(bytes.end(), once.begin(), once.end());
  bytes.insert(bytes.end(), once.begin(), once.end());
  m.bufferViews.push_back(view);
  tinygltf::Accessor out = a;
  out.bufferView = int(m.bufferViews.size()) - 1;
  out.byteOffset = 0;
  out.count = 2 * a.count;
  m.accessors.push_back(out);
  return int(m.accessors.size()) - 1;
}

// Testwuson with what morph-animated, vertex-painted characters carry: COLOR_0 red on the faces right of
// the middle and blue (half transparent) on the others, each getting brighter upwards, so that the middle
// is a colour seam (its vertices are split, as an exporter splits them); a lightmap-like TEXCOORD_1 (a
// planar projection, continuous across the seam); the morph target "Bulge" with NORMAL offsets.
std::string attributed_wuson(const fs::path& dir) {
  tinygltf::Model m = omsk_fixtures::testwuson(dir.string());
  int node = -1;
  for (size_t i = 0; i < m.nodes.size() && node < 0; ++i)
    if (m.nodes[i].skin >= 0 && m.nodes[i].mesh >= 0) node = int(i);
  if (node < 0) throw std::runtime_error("testwuson has no skinned mesh");
  for (auto& prim : m.meshes[m.nodes[node].mesh].primitives) {
    const int pos_acc = prim.attributes.at("POSITION");
    const size_t n = m.accessors[pos_acc].count;
    const std::vector<double> lo = m.accessors[pos_acc].minValues, hi = m.accessors[pos_acc].maxValues;
    const std::vector<double> pos = omsk_spec::read(m, pos_acc);
    for (auto& [name, acc] : prim.attributes) acc = doubled(m, acc);
    const std::vector<double> idx = omsk_spec::read(m, prim.indices);
    std::vector<uint32_t> out;
    const double mid = 0.5 * (lo[0] + hi[0]);
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
      const double cx = (pos[3 * size_t(idx[t])] + pos[3 * size_t(idx[t + 1])] + pos[3 * size_t(idx[t + 2])]) / 3.0;
      const uint32_t shift = cx < mid ? uint32_t(n) : 0;  // the left faces use the copies
      for (int k = 0; k < 3; ++k) out.push_back(uint32_t(idx[t + k]) + shift);
    }
    prim.indices = omsk_fixtures::add_index_accessor(m, out);
    std::vector<float> colour, uv1;
    for (size_t copy = 0; copy < 2; ++copy)
      for (size_t v = 0; v < n; ++v) {
        const float up = float(0.2 + 0.8 * (pos[3 * v + 1] - lo[1]) / (hi[1] - lo[1]));
        if (copy == 0)
          colour.insert(colour.end(), {up, 0.0f, 0.0f, 1.0f});
        else
          colour.insert(colour.end(), {0.0f, 0.0f, up, 0.5f});
        uv1.insert(uv1.end(),
                   {float((pos[3 * v] - lo[0]) / (hi[0] - lo[0])), float((pos[3 * v + 2] - lo[2]) / (hi[2] - lo[2]))});
      }
    prim.attributes["COLOR_0"] = omsk_fixtures::add_accessor(m, colour, TINYGLTF_TYPE_VEC4, 2 * n);
    prim.attributes["TEXCOORD_1"] = omsk_fixtures::add_accessor(m, uv1, TINYGLTF_TYPE_VEC2, 2 * n);
  }
  omsk_fixtures::add_morph_target(m);
  for (auto& prim : m.meshes[m.nodes[node].mesh].primitives) {
    // The bulge tilts the normals of what it moves outwards.
    const std::vector<double> d = omsk_spec::read(m, prim.targets.at(0).at("POSITION"));
    std::vector<float> dn(d.size(), 0.0f);
    for (size_t i = 0; i < d.size(); i += 3) dn[i] = float(4.0 * d[i + 1] * (d[i] >= 0 ? 1 : -1));
    prim.targets[0]["NORMAL"] = omsk_fixtures::add_accessor(m, dn, TINYGLTF_TYPE_VEC3, d.size() / 3);
  }
  const std::string path = (dir / "attributed_wuson.glb").string();
  omsk_spec::save_glb(m, path);
  return path;
}

struct Range {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  void add(double x) { lo = std::min(lo, x), hi = std::max(hi, x); }
};

// The per-component range of attribute \p name over every primitive of \p m.
std::vector<Range> attribute_range(const tinygltf::Model& m, const std::string& name) {
  std::vector<Range> r;
  for (const auto& mesh : m.meshes)
    for (const auto& prim : mesh.primitives) {
      const int a = prim.attributes.at(name);
      const int nc = omsk_spec::components(m.accessors[a]);
      r.resize(nc);
      const std::vector<double> x = omsk_spec::read(m, a);
      for (size_t i = 0; i < x.size(); ++i) r[i % nc].add(x[i]);
    }
  return r;
}

// Which side of the fixture's colour seam an RGBA colour is from: 0 red, 1 blue, -1 a blend (or neither).
int side(const double* c) {
  if (std::abs(c[1]) > 1e-6) return -1;
  if (std::abs(c[2]) <= 1e-6 && std::abs(c[3] - 1.0) <= 1e-6 && c[0] >= 0.2 - 1e-6) return 0;
  if (std::abs(c[0]) <= 1e-6 && std::abs(c[3] - 0.5) <= 1e-6 && c[2] >= 0.2 - 1e-6) return 1;
  return -1;
}

}  // namespace

TEST(VertexAttributes, ColoursSecondUvSetAndMorphNormalsSurviveTheCliAtHalfAndQuarter) {
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "cli");
  const std::string in = attributed_wuson(d);
  omsk_test::expect_valid_gltf(in);  // the fixture itself is sound
  const tinygltf::Model input = omsk_spec::load(in);
  const std::vector<Range> uv1_in = attribute_range(input, "TEXCOORD_1");

  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + in + "' -o lod.glb --lods 0.5,0.25 --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* name : {"lod_lod1.glb", "lod_lod2.glb"}) {
    SCOPED_TRACE(name);
    const std::string file = (d / name).string();
    omsk_test::expect_valid_gltf(file);
    const tinygltf::Model m = omsk_spec::load(file);
    ASSERT_FALSE(m.meshes.empty());
    size_t red = 0, blue = 0, vertices = 0;
    for (const auto& mesh : m.meshes)
      for (const auto& prim : mesh.primitives) {
        ASSERT_TRUE(prim.attributes.count("COLOR_0")) << "every primitive keeps its colours";
        ASSERT_TRUE(prim.attributes.count("TEXCOORD_1")) << "and its second UV set";
        ASSERT_TRUE(prim.attributes.count("TEXCOORD_0"));
        const tinygltf::Accessor& ca = m.accessors[prim.attributes.at("COLOR_0")];
        ASSERT_EQ(ca.type, TINYGLTF_TYPE_VEC4) << "RGBA stays RGBA";
        const std::vector<double> col = omsk_spec::read(m, prim.attributes.at("COLOR_0"));
        const size_t nv = col.size() / 4;
        vertices += nv;
        std::vector<int> sides(nv);
        for (size_t v = 0; v < nv; ++v) {
          sides[v] = side(&col[4 * v]);
          ASSERT_GE(sides[v], 0) << "vertex " << v << " has a colour blended across the seam: " << col[4 * v] << " "
                                 << col[4 * v + 1] << " " << col[4 * v + 2] << " " << col[4 * v + 3];
          for (int k = 0; k < 4; ++k) {
            EXPECT_GE(col[4 * v + k], 0.0);
            EXPECT_LE(col[4 * v + k], 1.0);
          }
          (sides[v] == 0 ? red : blue)++;
        }
        // Each triangle is painted from one side: the seam is still an edge of the surface, not smeared.
        const std::vector<double> idx = omsk_spec::read(m, prim.indices);
        for (size_t t = 0; t + 2 < idx.size(); t += 3)
          EXPECT_TRUE(sides[size_t(idx[t])] == sides[size_t(idx[t + 1])] &&
                      sides[size_t(idx[t])] == sides[size_t(idx[t + 2])])
              << "triangle " << t / 3 << " mixes the two sides' colours";
        ASSERT_EQ(prim.targets.size(), 1u);
        ASSERT_TRUE(prim.targets[0].count("NORMAL")) << "the morph target keeps its normal offsets";
        const std::vector<double> dn = omsk_spec::read(m, prim.targets[0].at("NORMAL"));
        ASSERT_EQ(dn.size(), 3 * nv);
        double largest = 0.0;
        for (double x : dn) {
          ASSERT_TRUE(std::isfinite(x));
          largest = std::max(largest, std::abs(x));
        }
        EXPECT_GT(largest, 0.01) << "the bulge changes the normals of what it moves";
      }
    EXPECT_GT(red, vertices / 10);
    EXPECT_GT(blue, vertices / 10);
    const std::vector<Range> uv1 = attribute_range(m, "TEXCOORD_1");
    ASSERT_EQ(uv1.size(), 2u);
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(uv1[k].lo, uv1_in[k].lo - 1e-6);
      EXPECT_LE(uv1[k].hi, uv1_in[k].hi + 1e-6);
      EXPECT_GT(uv1[k].hi - uv1[k].lo, 0.5 * (uv1_in[k].hi - uv1_in[k].lo)) << "a real UV set, not a constant";
    }
  }
}

TEST(VertexAttributes, TheIsolatedReadersArchiveCarriesEverySetAndTheMorphNormalFlag) {
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "archive");
  SkinnedMesh mesh;
  const ImportReport rep = import_skinned(attributed_wuson(d), mesh);
  const std::vector<CornerChannel> sets = corner_channels(mesh);
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0].kind, CornerKind::TexCoord);
  EXPECT_EQ(sets[0].set, 1);
  EXPECT_EQ(sets[1].kind, CornerKind::Color);
  EXPECT_EQ(sets[1].set, 0);
  ASSERT_EQ(morph_targets(mesh).size(), 1u);
  EXPECT_TRUE(morph_targets(mesh)[0].normals);

  SkinnedMesh back;
  ImportReport rep_back;
  load_import(save_import(mesh, rep), back, rep_back);
  const std::vector<CornerChannel> sets_back = corner_channels(back);
  ASSERT_EQ(sets_back.size(), sets.size());
  ASSERT_EQ(back.n_faces(), mesh.n_faces());
  ASSERT_EQ(morph_targets(back).size(), 1u);
  EXPECT_TRUE(morph_targets(back)[0].normals);
  // Faces are rebuilt in order, each from its first corner on: corners compare face by face.
  for (size_t i = 0; i < sets.size(); ++i)
    for (auto fh : mesh.faces()) {
      auto a = mesh.fh_range(fh).begin();
      auto b = back.fh_range(back.face_handle(fh.idx())).begin();
      for (int k = 0; k < 3; ++k, ++a, ++b) {
        ASSERT_EQ(mesh.to_vertex_handle(*a).idx(), back.to_vertex_handle(*b).idx());
        ASSERT_EQ(mesh.property(sets[i].handle, *a), back.property(sets_back[i].handle, *b));
      }
    }
}

TEST(VertexAttributes, AnimatedMorphCubeKeepsItsMorphNormalsAtRatioOne) {
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "cube");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + morph_cube + "' -o cube.gltf --ratio 1", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("the input's tangents (TANGENT, and morph targets' tangent offsets) are not kept"),
            std::string::npos)
      << "dropping the input's tangents is said: " << r.out;
  const std::string file = (d / "cube.gltf").string();
  omsk_test::expect_valid_gltf(file);

  // The input in world space (its one node's rotation and uniform scale), one row per glTF vertex.
  struct Row {
    Eigen::Vector3d p, n;
    std::vector<Eigen::Vector3d> morphed_n;  // per target: normalised N + dN
  };
  auto rows = [](const tinygltf::Model& m, const Eigen::Affine3d& world) {
    std::vector<Row> out;
    const auto& prim = m.meshes.at(0).primitives.at(0);
    const std::vector<double> p = omsk_spec::read(m, prim.attributes.at("POSITION")),
                              n = omsk_spec::read(m, prim.attributes.at("NORMAL"));
    std::vector<std::vector<double>> dn;
    for (const auto& t : prim.targets) {
      EXPECT_TRUE(t.count("NORMAL"));
      dn.push_back(t.count("NORMAL") ? omsk_spec::read(m, t.at("NORMAL")) : std::vector<double>(n.size(), 0.0));
    }
    for (size_t v = 0; v < p.size() / 3; ++v) {
      Row row;
      row.p = world * Eigen::Vector3d(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
      row.n = (world.linear() * Eigen::Vector3d(n[3 * v], n[3 * v + 1], n[3 * v + 2])).normalized();
      for (const auto& t : dn)
        row.morphed_n.push_back((world.linear() * Eigen::Vector3d(n[3 * v] + t[3 * v], n[3 * v + 1] + t[3 * v + 1],
                                                                  n[3 * v + 2] + t[3 * v + 2]))
                                    .normalized());
      out.push_back(row);
    }
    return out;
  };
  const tinygltf::Model in = omsk_spec::load(morph_cube), out = omsk_spec::load(file);
  const tinygltf::Node& node = in.nodes.at(0);
  ASSERT_EQ(node.rotation.size(), 4u);
  ASSERT_EQ(node.scale.size(), 3u);
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  world.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
  world.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  // The output stores the mesh where a viewer shows it in the rest pose (in world space).
  const std::vector<Row> a = rows(in, world), b = rows(out, Eigen::Affine3d::Identity());
  ASSERT_EQ(out.meshes.at(0).primitives.at(0).targets.size(), 2u);
  double worst = 0.0;
  for (const Row& x : a) {
    const Row* match = nullptr;
    for (const Row& y : b)
      if ((x.p - y.p).norm() < 1e-4 && x.n.dot(y.n) > 0.99) match = &y;
    ASSERT_NE(match, nullptr) << "input vertex at " << x.p.transpose() << " normal " << x.n.transpose();
    for (size_t t = 0; t < x.morphed_n.size(); ++t)
      worst = std::max(worst, std::acos(std::clamp(x.morphed_n[t].dot(match->morphed_n[t]), -1.0, 1.0)));
  }
  // At full weight a viewer shades each target with the input's normals (flat faces: recomputed exactly).
  EXPECT_LT(worst * 180.0 / M_PI, 0.1);
}

TEST(VertexAttributes, RgbColoursOfAnotherFormatComeOutAsVec3WithTheInputsValues) {
  // An X file with per-vertex colours (assimp reports them with alpha 1), kept whole at --ratio 1.
  const std::string in = std::string(OMSK_TEST_MODELS) + "/X/kwxport_test_cubewithvcolors.x";
  std::set<std::array<float, 3>> expected;
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(in, aiProcess_Triangulate);
  ASSERT_NE(scene, nullptr);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    ASSERT_TRUE(am->HasVertexColors(0));
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      EXPECT_EQ(am->mColors[0][v].a, 1.0f);
      expected.insert({am->mColors[0][v].r, am->mColors[0][v].g, am->mColors[0][v].b});
    }
  }
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "rgb");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + in + "' -o cube.glb --ratio 1 --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  omsk_test::expect_valid_gltf((d / "cube.glb").string());
  const tinygltf::Model m = omsk_spec::load((d / "cube.glb").string());
  std::set<std::array<float, 3>> written;
  for (const auto& mesh : m.meshes)
    for (const auto& prim : mesh.primitives) {
      ASSERT_TRUE(prim.attributes.count("COLOR_0"));
      EXPECT_FALSE(prim.attributes.count("COLOR_1")) << "only the sets the input had";
      EXPECT_FALSE(prim.attributes.count("TEXCOORD_1"));
      ASSERT_EQ(m.accessors[prim.attributes.at("COLOR_0")].type, TINYGLTF_TYPE_VEC3);
      const std::vector<double> c = omsk_spec::read(m, prim.attributes.at("COLOR_0"));
      for (size_t i = 0; i + 2 < c.size(); i += 3) written.insert({float(c[i]), float(c[i + 1]), float(c[i + 2])});
    }
  EXPECT_EQ(written, expected);
}

TEST(VertexAttributes, PartsOfTheInputWithoutColoursAreWhiteNotUndefined) {
  // Two skinned meshes, only the first painted: merged into one, the second's corners get white, which is
  // how a viewer showed that mesh without COLOR_0.
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "partial");
  tinygltf::Model m = omsk_fixtures::testwuson(d.string());
  omsk_fixtures::split_into_second_skin(m);
  tinygltf::Primitive& painted = m.meshes.at(0).primitives.at(0);
  const size_t n = m.accessors[painted.attributes.at("POSITION")].count;
  std::vector<float> colour;
  for (size_t v = 0; v < n; ++v) colour.insert(colour.end(), {0.5f, 0.25f, 0.0f, 1.0f});
  painted.attributes["COLOR_0"] = omsk_fixtures::add_accessor(m, colour, TINYGLTF_TYPE_VEC4, n);
  ASSERT_EQ(m.meshes.size(), 2u);
  ASSERT_FALSE(m.meshes[1].primitives.at(0).attributes.count("COLOR_0"));
  const std::string in = (d / "partly_painted.glb").string();
  omsk_spec::save_glb(m, in);

  SkinnedMesh mesh;
  import_skinned(in, mesh);
  const std::vector<CornerChannel> sets = corner_channels(mesh);
  ASSERT_EQ(sets.size(), 1u);
  size_t white = 0, painted_corners = 0;
  for (auto fh : mesh.faces())
    for (auto h : mesh.fh_range(fh)) {
      const OpenMesh::Vec4f c = mesh.property(sets[0].handle, h);
      if (c == OpenMesh::Vec4f(1, 1, 1, 1))
        ++white;
      else if (c == OpenMesh::Vec4f(0.5f, 0.25f, 0.0f, 1.0f))
        ++painted_corners;
      else
        ADD_FAILURE() << "corner colour " << c;
    }
  EXPECT_GT(white, mesh.n_faces());  // about half of the 3 corners per face each
  EXPECT_GT(painted_corners, mesh.n_faces());
}

TEST(VertexAttributes, ASecondUvSetComesBackAsItWasAtRatioOne) {
  // BoxTexcoords has TEXCOORD_0 and TEXCOORD_1: every (UV0, UV1) pair of the input is in the output and
  // no other (both sets in glTF's top-left convention, as the file has them).
  const std::string in = std::string(OMSK_TEST_MODELS) + "/glTF2/BoxTexcoords-glTF/boxTexcoords.gltf";
  const fs::path d = omsk_test::scratch_dir("vertex_attributes", "uv1");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + in + "' -o box.glb --ratio 1 --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  omsk_test::expect_valid_gltf((d / "box.glb").string());
  auto pairs = [](const tinygltf::Model& m) {
    std::set<std::array<long, 4>> out;
    for (const auto& mesh : m.meshes)
      for (const auto& prim : mesh.primitives) {
        EXPECT_TRUE(prim.attributes.count("TEXCOORD_1"));
        if (!prim.attributes.count("TEXCOORD_1")) continue;
        const std::vector<double> a = omsk_spec::read(m, prim.attributes.at("TEXCOORD_0")),
                                  b = omsk_spec::read(m, prim.attributes.at("TEXCOORD_1"));
        for (size_t i = 0; i + 1 < a.size(); i += 2)
          out.insert({std::lround(a[i] * 1e5), std::lround(a[i + 1] * 1e5), std::lround(b[i] * 1e5),
                      std::lround(b[i + 1] * 1e5)});
      }
    return out;
  };
  const auto expected = pairs(omsk_spec::load(in));
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(pairs(omsk_spec::load((d / "box.glb").string())), expected);
}
