// GltfValueCheck: a NaN skin weight is refused, not silently dropped by the reader.
#include "gltf_spec.hh"

#include <OpenMeshSkinned/IO/GltfValueCheck.hh>
#include <OpenMeshSkinned/IO/Import.hh>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {
const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";

// simple_skin with weight \p c of vertex \p v set to \p value, as .gltf with inline buffers.
fs::path with_weight(float value, size_t v, size_t c) {
  const fs::path d = fs::temp_directory_path() / ("omsk_valuecheck_" + std::to_string(::getpid()));
  fs::create_directories(d);
  tinygltf::Model m = omsk_spec::load(simple_skin);
  const auto& acc = m.accessors[m.meshes[0].primitives[0].attributes.at("WEIGHTS_0")];
  const auto& view = m.bufferViews[acc.bufferView];
  const size_t stride = view.byteStride ? view.byteStride : 16;
  std::memcpy(m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset + v * stride + c * 4, &value, 4);
  const fs::path out = d / "w.gltf";
  tinygltf::TinyGLTF w;
  EXPECT_TRUE(w.WriteGltfSceneToFile(&m, out.string(), true, true, true, false));
  return out;
}
}  // namespace

TEST(GltfValueCheck, NonFiniteWeightIsAnErrorNamingTheVertex) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const auto f = with_weight(bad, 2, 0);
    try {
      check_gltf_weights(f.string(), "shown.gltf");
      FAIL() << "accepted a non-finite weight";
    } catch (const IOError& e) {
      EXPECT_STREQ(e.what(), "shown.gltf: vertex 2 of mesh 0 (\"\") has a non-finite weight in WEIGHTS_0");
    }
    SkinnedMesh mesh;
    EXPECT_THROW(import_skinned(f.string(), mesh), IOError);
  }
}

TEST(GltfValueCheck, FiniteWeightsAndOtherFormatsPass) {
  EXPECT_NO_THROW(check_gltf_weights(with_weight(0.5f, 2, 0).string(), "x"));
  EXPECT_NO_THROW(check_gltf_weights(simple_skin, "x"));
  EXPECT_NO_THROW(check_gltf_weights(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", "x"));
}
