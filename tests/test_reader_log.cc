// ReaderLog: data a reader drops is reported as an import warning, its routine chatter is not.
#include "gltf_spec.hh"

#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ReaderLog.hh>

#include <assimp/DefaultLogger.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

TEST(ReaderLog, RecognisesDataLoss) {
  EXPECT_TRUE(ReaderLog::reports_data_loss("Some faces had out-of-range indices. Those faces were dropped."));
  EXPECT_TRUE(ReaderLog::reports_data_loss("Skipping invalid animation channel"));
  EXPECT_FALSE(ReaderLog::reports_data_loss("Validation warning: aiMesh::mVertices[0]: bone weight sum != 1.0"));
  EXPECT_FALSE(ReaderLog::reports_data_loss("Unknown data object in frame in x file"));
}

TEST(ReaderLog, FacesWithOutOfRangeIndicesAreNotDroppedSilently) {
  const fs::path d = fs::temp_directory_path() / ("omsk_readerlog_" + std::to_string(::getpid()));
  fs::create_directories(d);
  tinygltf::Model m = omsk_spec::load(std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf");
  const auto& acc = m.accessors[m.meshes[0].primitives[0].indices];
  const auto& view = m.bufferViews[acc.bufferView];
  ASSERT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  auto* first = reinterpret_cast<uint16_t*>(m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset);
  *first = 99;           // the mesh has 10 vertices
  tinygltf::TinyGLTF w;  // .gltf with the buffers inline (a GLB holds one buffer, simple_skin has four)
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, (d / "oor.gltf").string(), true, true, true, false));

  SkinnedMesh mesh;
  const ImportReport r = import_skinned((d / "oor.gltf").string(), mesh);
  EXPECT_EQ(r.faces, 7u);  // assimp dropped one of the eight
  EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
    return w.find("the reader dropped data") != std::string::npos && w.find("out-of-range") != std::string::npos;
  }));
  // The routine validation chatter (FBX weight sums) does not reach the user.
  SkinnedMesh fbx;
  const ImportReport rf = import_skinned(std::string(OMSK_TEST_MODELS) + "/FBX/animation_with_skeleton.fbx", fbx);
  for (const auto& w : rf.warnings) EXPECT_EQ(w.find("the reader dropped data"), std::string::npos) << w;
}

TEST(ReaderLog, AFloodOfDistinctMessagesStaysBounded) {
  // A corrupt file can make a reader log a distinct line per element, millions of them.
  const ReaderLog log;
  for (int i = 0; i < 100000; ++i)
    Assimp::DefaultLogger::get()->warn(("Skipping element " + std::to_string(i)).c_str());
  const auto lines = log.data_loss();
  ASSERT_EQ(lines.size(), ReaderLog::kMaxDistinct + 1);
  EXPECT_EQ(lines.front(), "Skipping element 0");
  EXPECT_EQ(lines.back(), "and " + std::to_string(100000 - ReaderLog::kMaxDistinct) + " more such messages");
}
