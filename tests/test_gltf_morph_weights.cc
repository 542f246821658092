// Negative morph weights (GltfMorphWeights): assimp 5.2 clamps them to 0, so a target driven below zero
// would stop at rest; the importer takes the file's own signed keys. Judged by the independent spec poser.
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/GltfMorphWeights.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {

const std::string cube =
    std::string(OMSK_TEST_MODELS) + "/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";

// AnimatedMorphCube (two targets, one weights channel) with its first target's weights negated (or, not
// \p negate, every weight made non-negative: the file has one of -1.5e-7), written as \p name; \p unnamed:
// its node without a name.
std::string negated_cube(const fs::path& dir, const std::string& name, bool unnamed, bool negate = true) {
  tinygltf::Model m = omsk_spec::load(cube);
  const tinygltf::Accessor& acc = m.accessors[size_t(m.animations[0].samplers[0].output)];
  const tinygltf::BufferView& view = m.bufferViews[size_t(acc.bufferView)];
  auto* w = reinterpret_cast<float*>(m.buffers[size_t(view.buffer)].data.data() + view.byteOffset + acc.byteOffset);
  for (size_t i = 0; i < acc.count; ++i) w[i] = negate && i % 2 == 0 ? -w[i] : std::abs(w[i]);
  m.accessors[size_t(m.animations[0].samplers[0].output)].minValues.clear();
  m.accessors[size_t(m.animations[0].samplers[0].output)].maxValues.clear();
  if (unnamed) m.nodes[0].name.clear();
  const std::string path = (dir / name).string();
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, path, true, true, true, false));
  return path;
}

double worst_over_clip(const std::string& a_path, const std::string& b_path) {
  const tinygltf::Model a = omsk_spec::load(a_path), b = omsk_spec::load(b_path);
  double worst = 0.0;
  const double d = omsk_spec::duration(a, 0);
  for (int k = 0; k <= 20; ++k) {
    const auto pa = omsk_spec::pose(a, 0, d * k / 20.0), pb = omsk_spec::pose(b, 0, d * k / 20.0);
    worst = std::max({worst, omsk_spec::max_nearest_distance(pa, pb), omsk_spec::max_nearest_distance(pb, pa)});
  }
  return worst / omsk_spec::diagonal(omsk_spec::pose(a, -1, 0.0));
}

}  // namespace

TEST(GltfMorphWeights, OnlyChannelsWithANegativeWeightAreRead) {
  std::vector<std::string> warnings;
  const fs::path d = omsk_test::scratch_dir("morph_weights", "read");
  EXPECT_TRUE(
      detail::read_signed_morph_weights(negated_cube(d, "positive.gltf", false, false), warnings).channels.empty());
  const auto signed_weights = detail::read_signed_morph_weights(negated_cube(d, "named.gltf", false), warnings);
  const auto* ch = signed_weights.find(0, "AnimatedMorphCube");
  ASSERT_NE(ch, nullptr);
  EXPECT_EQ(ch->values.size(), 2 * ch->keys);
  EXPECT_LT(*std::min_element(ch->values.begin(), ch->values.end()), -0.5);
  const auto unnamed = detail::read_signed_morph_weights(negated_cube(d, "unnamed.gltf", true), warnings);
  EXPECT_NE(unnamed.find(0, "nodes[0]"), nullptr);
  EXPECT_TRUE(warnings.empty());
}

TEST(GltfMorphWeights, NegativeWeightsArriveAndTheLodMovesLikeTheInput) {
  for (const bool unnamed : {false, true}) {
    const fs::path d = omsk_test::scratch_dir("morph_weights", unnamed ? "unnamed" : "named");
    const std::string in = negated_cube(d, "in.gltf", unnamed);
    SkinnedMesh mesh;
    import_skinned(in, mesh);
    ASSERT_EQ(clips(mesh).size(), 1u);
    double lowest = 0.0;
    for (const MorphChannel& mc : clips(mesh)[0].morph_channels)
      for (double w : mc.weights) lowest = std::min(lowest, w);
    EXPECT_LT(lowest, -0.5) << "unnamed " << unnamed;
    const auto r = omsk_test::run_command(OMSK_CLI_EXE, "in.gltf -o out.glb --ratio 1", d);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_LT(worst_over_clip(in, (d / "out.glb").string()), 1e-4) << "unnamed " << unnamed;
    omsk_test::expect_valid_gltf((d / "out.glb").string());
  }
}
