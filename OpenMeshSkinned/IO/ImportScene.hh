#pragma once
/** \file ImportScene.hh
 *  Steps of the import that read assimp's scene graph: its nodes with their world matrices, the mesh
 *  instances, the joints (and twins) that the skins and rigid meshes need, and the animation clips.
 *  Internal to the importer (Import.cc); the public entry point is import_skinned().
 */

#include "OpenMeshSkinned/IO/GltfMorphWeights.hh"
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

/** The joints of the imported skeleton: the input's own joints, each bound where its node rests. Those
 *  are every bone of a skin, the node of every mesh that needs one to move with (a mesh without a skin,
 *  or a skinned mesh with vertices no bone weights), and an ancestor of these only when it moves them in
 *  a way their own transforms cannot carry: when it is animated, or when its transform is not a
 *  similarity (shear or a mirror cannot be folded into a child's translation, rotation and scale). Every
 *  other ancestor (the armature node Blender writes above the bones, the reader's root above several top
 *  nodes, a rotated and scaled scene root, the skinned mesh's own node) is folded into the rest transform
 *  and the keys of the joints below it: no engine sharing one skeleton across LODs knows such joints.
 *  A skin whose inverse bind for a node differs from the one already in use (several skins bound in
 *  different poses or spaces) gets a twin joint: same parent, same transform, same animation, own bind. */
class JointMap {
public:
  /// Fills \p skel; \p path names the file in errors.
  JointMap(const aiScene* scene, const SceneNodes& sn, const std::vector<MeshInstance>& instances, Skeleton& skel,
           const std::string& path);
  JointMap(const JointMap&) = delete;
  JointMap& operator=(const JointMap&) = delete;

  bool any_bones() const { return any_bones_; }
  /// The node of a bone (an IOError when the scene has none of that name).
  int bone_node(const aiBone* b) const;
  /// The joint of \p node bound with inverse bind \p ib: the node's own joint, or a twin.
  int joint_for(int node, const Eigen::Matrix4d& ib);
  const std::vector<int>& joints_of_node(int node) const { return joints_of_node_[node]; }
  /// The similarity of the ancestors folded into \p node's joint (identity when none): the node's clip keys,
  /// relative to its parent node, become relative to its parent joint through it.
  const Eigen::Matrix4d& folded_above(int node) const { return folded_above_[node]; }
  size_t twins() const { return twins_; }

private:
  const SceneNodes& sn_;
  Skeleton& skel_;
  std::string path_;
  std::vector<std::vector<int>> joints_of_node_;
  std::vector<Eigen::Matrix4d> folded_above_;
  std::vector<char> claimed_;
  bool any_bones_ = false;
  size_t twins_ = 0;
};

/** The scene's animations as clips of \p mesh: joint channels (twins move with their node) and morph
 *  weight channels (\p target_base: the first morph target of each instance), their weights taken from
 *  \p signed_weights where it has the channel (assimp clamps negative ones). What cannot be kept is said
 *  in \p warnings. */
void read_clips(const aiScene* scene, const SceneNodes& sn, const JointMap& joints,
                const std::vector<MeshInstance>& instances, const std::vector<size_t>& target_base,
                const SignedMorphWeights& signed_weights, SkinnedMesh& mesh, std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned::detail
