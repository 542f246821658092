#pragma once
/** \file ImportScene.hh
 *  Steps of the import that read assimp's scene graph: its nodes with their world matrices, the mesh
 *  instances, the joints (and twins) that the skins and rigid meshes need, and the animation clips.
 *  Internal to the importer (Import.cc); the public entry point is import_skinned().
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <assimp/scene.h>

#include <Eigen/Core>

#include <string>
#include <unordered_map>
#include <vector>

namespace OpenMeshSkinned::detail {

Eigen::Matrix4d to_matrix(const aiMatrix4x4& m);

/// The scene's nodes in pre-order (parents first) with their world matrices.
struct SceneNodes {
  std::vector<const aiNode*> nodes;
  std::vector<int> parent;
  std::vector<Eigen::Matrix4d> global;
  std::unordered_map<std::string, int> by_name;  ///< first one wins, as assimp's FindNode does

  explicit SceneNodes(const aiNode* root) { visit(root, -1); }

private:
  void visit(const aiNode* n, int p);
};

/// A triangle mesh placed by a node; a mesh used by several nodes is instanced several times.
struct MeshInstance {
  int node;
  unsigned mesh;
};
std::vector<MeshInstance> mesh_instances(const aiScene* scene, const SceneNodes& sn);

/** The joints of the imported skeleton: every bone, every node carrying a mesh, and their ancestors
 *  (ancestors move the bones when animated, and a rotated, scaled scene root is part of every pose), each
 *  bound where its node rests. A skin whose inverse bind for a node differs from the one already in use
 *  (several skins bound in different poses or spaces) gets a twin joint: same parent, same transform, same
 *  animation, own bind. */
class JointMap {
public:
  /// Fills \p skel; \p path names the file in errors.
  JointMap(const aiScene* scene, const SceneNodes& sn, const std::vector<MeshInstance>& instances, Skeleton& skel,
           const std::string& path);

  bool any_bones() const { return any_bones_; }
  /// The node of a bone (an IOError when the scene has none of that name).
  int bone_node(const aiBone* b) const;
  /// The joint of \p node bound with inverse bind \p ib: the node's own joint, or a twin.
  int joint_for(int node, const Eigen::Matrix4d& ib);
  const std::vector<int>& joints_of_node(int node) const { return joints_of_node_[node]; }
  size_t twins() const { return twins_; }

private:
  const SceneNodes& sn_;
  Skeleton& skel_;
  std::string path_;
  std::vector<std::vector<int>> joints_of_node_;
  std::vector<char> claimed_;
  bool any_bones_ = false;
  size_t twins_ = 0;
};

/** The scene's animations as clips of \p mesh: joint channels (twins move with their node) and morph
 *  weight channels (\p target_base: the first morph target of each instance). What cannot be kept is said
 *  in \p warnings. */
void read_clips(const aiScene* scene, const SceneNodes& sn, const JointMap& joints,
                const std::vector<MeshInstance>& instances, const std::vector<size_t>& target_base, SkinnedMesh& mesh,
                std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned::detail
