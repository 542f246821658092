// FBX pivots: the skeleton is the file's own bones. assimp's reader would otherwise insert helper nodes
// ("Bone_$AssimpFbx$_Translation", "..._PreRotation", ...) that no engine knows; folded into their bones,
// the character must still rest exactly where the reader's own node chain puts it.
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <string>

using namespace OpenMeshSkinned;

namespace {

using Key = std::array<long long, 3>;
Key key(double x, double y, double z) { return {std::llround(x * 1e4), std::llround(y * 1e4), std::llround(z * 1e4)}; }

// Every vertex where the reader's node chain (helpers and all) puts it, rounded to 1e-4.
std::set<Key> positions_with_helper_nodes(const std::string& path, bool& had_helpers) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  EXPECT_NE(scene, nullptr) << importer.GetErrorString();
  std::set<Key> out;
  had_helpers = false;
  struct Walk {
    const aiScene* scene;
    std::set<Key>& out;
    bool& helpers;
    void operator()(const aiNode* n, const aiMatrix4x4& parent) {
      const aiMatrix4x4 global = parent * n->mTransformation;
      helpers |= std::string(n->mName.C_Str()).find("$AssimpFbx$") != std::string::npos;
      for (unsigned m = 0; m < n->mNumMeshes; ++m) {
        const aiMesh* am = scene->mMeshes[n->mMeshes[m]];
        for (unsigned v = 0; v < am->mNumVertices; ++v) {
          const aiVector3D p = global * am->mVertices[v];
          out.insert(key(p.x, p.y, p.z));
        }
      }
      for (unsigned c = 0; c < n->mNumChildren; ++c) (*this)(n->mChildren[c], global);
    }
  } walk{scene, out, had_helpers};
  if (scene) walk(scene->mRootNode, aiMatrix4x4());
  return out;
}

}  // namespace

TEST(FbxPivots, HelperNodesAreFoldedIntoTheBonesAndTheRestShapeIsUnchanged) {
  for (const char* name : {"cubes_with_mirroring_and_pivot.fbx", "maxPbrMaterial_metalRough.fbx"}) {
    const std::string path = std::string(OMSK_TEST_MODELS) + "/FBX/" + name;
    bool had_helpers = false;
    const std::set<Key> expected = positions_with_helper_nodes(path, had_helpers);
    EXPECT_TRUE(had_helpers) << name << ": the reader makes no helper nodes here, so this test tests nothing";
    SkinnedMesh mesh;
    import_skinned(path, mesh);
    for (const Joint& j : skeleton(mesh).joints)
      EXPECT_EQ(j.name.find("$AssimpFbx$"), std::string::npos) << name << ": " << j.name;
    std::set<Key> got;
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      got.insert(key(p[0], p[1], p[2]));
    }
    EXPECT_EQ(got, expected) << name;
  }
}
