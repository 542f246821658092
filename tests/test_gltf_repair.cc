// GltfRepair: valid glTF that assimp 5.2 would crash on (skins without inverseBindMatrices) is read,
// and poses as the specification says (identity inverse binds).
#include "gltf_spec.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/GltfRepair.hh>
#include <OpenMeshSkinned/IO/Import.hh>

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("omsk_repair_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";

// A GLB holds one binary buffer: simple_skin has four.
void merge_buffers(tinygltf::Model& m) {
  std::vector<size_t> base;
  std::vector<unsigned char> all;
  for (const auto& b : m.buffers) {
    while (all.size() % 4) all.push_back(0);
    base.push_back(all.size());
    all.insert(all.end(), b.data.begin(), b.data.end());
  }
  for (auto& v : m.bufferViews) {
    v.byteOffset += base[v.buffer];
    v.buffer = 0;
  }
  m.buffers.resize(1);
  m.buffers[0].data = all;
  m.buffers[0].uri.clear();
}

// simple_skin without its inverse bind matrices, as .gltf and as .glb.
fs::path without_inverse_binds(const fs::path& dir, bool glb) {
  tinygltf::Model m = omsk_spec::load(simple_skin);
  for (auto& s : m.skins) s.inverseBindMatrices = -1;
  if (glb) merge_buffers(m);
  const fs::path out = dir / (glb ? "noibm.glb" : "noibm.gltf");
  tinygltf::TinyGLTF w;
  EXPECT_TRUE(w.WriteGltfSceneToFile(&m, out.string(), true, true, true, glb));
  return out;
}

void expect_poses_as_the_spec_says(const fs::path& in, const fs::path& dir) {
  SkinnedMesh mesh;
  ImportOptions o;
  o.isolate = true;  // a regression would crash assimp: let it fail the test, not the test binary
  ASSERT_NO_THROW(import_skinned(in.string(), mesh, o));
  const fs::path out = dir / "out.glb";
  export_gltf(mesh, out.string());
  const auto src = omsk_spec::load(in.string());
  const auto ours = omsk_spec::load(out.string());
  for (double t : {0.0, 1.3, 2.7}) {
    const auto a = omsk_spec::pose(src, 0, t), b = omsk_spec::pose(ours, 0, t);
    EXPECT_LT(omsk_spec::max_nearest_distance(a, b), 1e-4 * omsk_spec::diagonal(a)) << in << " at " << t;
  }
}
}  // namespace

TEST(GltfRepair, SkinWithoutInverseBindMatricesGltf) {
  const auto d = scratch("gltf");
  expect_poses_as_the_spec_says(without_inverse_binds(d, false), d);
}

TEST(GltfRepair, SkinWithoutInverseBindMatricesGlb) {
  const auto d = scratch("glb");
  expect_poses_as_the_spec_says(without_inverse_binds(d, true), d);
}

TEST(GltfRepair, ExternalBuffersAreFoundAndTheCopyIsRemoved) {
  const auto d = scratch("external");
  tinygltf::Model m = omsk_spec::load(simple_skin);
  for (auto& s : m.skins) s.inverseBindMatrices = -1;
  fs::create_directories(d / "bin");
  for (size_t i = 0; i < m.buffers.size(); ++i) m.buffers[i].uri = "bin/b" + std::to_string(i) + ".bin";
  tinygltf::TinyGLTF w;
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, (d / "ext.gltf").string(), true, false, true, false));
  ASSERT_TRUE(fs::exists(d / "bin" / "b0.bin"));
  std::string copy_dir;
  {
    const RepairedGltf r((d / "ext.gltf").string());
    ASSERT_FALSE(r.path().empty());
    copy_dir = fs::path(r.path()).parent_path().string();
    EXPECT_TRUE(fs::exists(fs::path(copy_dir) / "bin" / "b0.bin"));
  }
  EXPECT_FALSE(fs::exists(copy_dir));
  expect_poses_as_the_spec_says(d / "ext.gltf", d);
}

TEST(GltfRepair, FilesThatNeedNoneAreReadAsTheyAre) {
  EXPECT_TRUE(RepairedGltf(simple_skin).path().empty());
  EXPECT_TRUE(RepairedGltf(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X").path().empty());
}

// A GLB whose buffers are all data URIs has no binary chunk (tinygltf writes simple_skin's four so);
// assimp 5.2 would take the first for the missing chunk and refuse the file.
TEST(GltfRepair, AGlbWithoutABinaryChunkIsReadThroughAGltfCopy) {
  const auto d = scratch("no_bin_chunk");
  tinygltf::Model m = omsk_spec::load(simple_skin);
  const fs::path in = d / "uris.glb";
  tinygltf::TinyGLTF w;
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, in.string(), true, true, true, true));
  {
    const RepairedGltf r(in.string());
    ASSERT_FALSE(r.path().empty());
    EXPECT_EQ(fs::path(r.path()).extension(), ".gltf");
  }
  expect_poses_as_the_spec_says(in, d);
}
