#include "OpenMeshSkinned/IO/ImportScene.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <Eigen/LU>

#include <algorithm>

namespace OpenMeshSkinned::detail {

Eigen::Matrix4d to_matrix(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return e;
}

void SceneNodes::visit(const aiNode* n, int p) {
  const int i = static_cast<int>(nodes.size());
  nodes.push_back(n);
  parent.push_back(p);
  global.push_back(p < 0 ? to_matrix(n->mTransformation) : Eigen::Matrix4d(global[p] * to_matrix(n->mTransformation)));
  by_name.emplace(n->mName.C_Str(), i);
  for (unsigned c = 0; c < n->mNumChildren; ++c) visit(n->mChildren[c], i);
}

std::vector<MeshInstance> mesh_instances(const aiScene* scene, const SceneNodes& sn) {
  std::vector<MeshInstance> out;
  for (size_t i = 0; i < sn.nodes.size(); ++i)
    for (unsigned k = 0; k < sn.nodes[i]->mNumMeshes; ++k) {
      const aiMesh* am = scene->mMeshes[sn.nodes[i]->mMeshes[k]];
      if (am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) out.push_back({static_cast<int>(i), sn.nodes[i]->mMeshes[k]});
    }
  return out;
}

JointMap::JointMap(const aiScene* scene, const SceneNodes& sn, const std::vector<MeshInstance>& instances,
                   Skeleton& skel, const std::string& path)
    : sn_(sn), skel_(skel), path_(path), joints_of_node_(sn.nodes.size()) {
  std::vector<char> needed(sn.nodes.size(), 0);
  auto need = [&](int n) {
    for (; n >= 0 && !needed[n]; n = sn.parent[n]) needed[n] = 1;
  };
  for (const MeshInstance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    need(in.node);  // an unskinned mesh moves with it; a skinned one binds unweighted vertices to it
    any_bones_ |= am->mNumBones > 0;
    for (unsigned b = 0; b < am->mNumBones; ++b) need(bone_node(am->mBones[b]));
  }
  for (size_t i = 0; i < sn.nodes.size(); ++i) {
    if (!needed[i]) continue;
    Joint j;
    j.name = sn.nodes[i]->mName.C_Str();
    j.parent = sn.parent[i] < 0 ? -1 : joints_of_node_[sn.parent[i]].front();
    j.rest_local = to_matrix(sn.nodes[i]->mTransformation);
    j.inverse_bind = sn.global[i].inverse();
    joints_of_node_[i].push_back(skel.size());
    skel.joints.push_back(j);
    claimed_.push_back(0);
  }
}

int JointMap::bone_node(const aiBone* b) const {
  auto it = sn_.by_name.find(b->mName.C_Str());
  if (it == sn_.by_name.end()) throw IOError(path_ + ": bone \"" + b->mName.C_Str() + "\" has no node in the scene");
  return it->second;
}

int JointMap::joint_for(int node, const Eigen::Matrix4d& ib) {
  const double tol = 1e-5 * std::max(1.0, ib.cwiseAbs().maxCoeff());
  for (int j : joints_of_node_[node])
    if ((skel_.joints[j].inverse_bind - ib).cwiseAbs().maxCoeff() <= tol) return claimed_[j] = 1, j;
  const int first = joints_of_node_[node].front();
  if (!claimed_[first]) {
    skel_.joints[first].inverse_bind = ib;
    claimed_[first] = 1;
    return first;
  }
  Joint twin = skel_.joints[first];
  twin.inverse_bind = ib;
  joints_of_node_[node].push_back(skel_.size());
  skel_.joints.push_back(twin);
  claimed_.push_back(1);
  ++twins_;
  return skel_.size() - 1;
}

}  // namespace OpenMeshSkinned::detail
