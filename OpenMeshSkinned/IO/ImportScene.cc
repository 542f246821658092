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

namespace {

// Whether some vertex of a skinned mesh has no bone weight record (not even a zero): read_weights() binds
// those to the mesh's node, which must then be a joint.
bool has_unweighted_vertex(const aiMesh* am) {
  std::vector<char> touched(am->mNumVertices, 0);
  for (unsigned b = 0; b < am->mNumBones; ++b)
    for (unsigned w = 0; w < am->mBones[b]->mNumWeights; ++w)
      if (am->mBones[b]->mWeights[w].mVertexId < am->mNumVertices) touched[am->mBones[b]->mWeights[w].mVertexId] = 1;
  return std::find(touched.begin(), touched.end(), 0) != touched.end();
}

// A rotation, a positive uniform scale and a translation: a child's TRS composed with it is again a TRS,
// so the node can be folded into its children (their rest transforms and keys) without a joint of its own.
bool is_similarity(const Eigen::Matrix4d& m) {
  if (!m.allFinite() || (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) return false;
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  const double s2 = (a.transpose() * a).trace() / 3.0;
  if (!(s2 > 0.0) || a.determinant() <= 0.0) return false;
  return ((a.transpose() * a) / s2 - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6;
}

}  // namespace

JointMap::JointMap(const aiScene* scene, const SceneNodes& sn, const std::vector<MeshInstance>& instances,
                   Skeleton& skel, const std::string& path)
    : sn_(sn),
      skel_(skel),
      path_(path),
      joints_of_node_(sn.nodes.size()),
      folded_above_(sn.nodes.size(), Eigen::Matrix4d::Identity()) {
  const size_t n = sn.nodes.size();
  std::vector<char> own(n, 0), animated(n, 0), above(n, 0);  // above: the node or a descendant is own
  for (const MeshInstance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    any_bones_ |= am->mNumBones > 0;
    for (unsigned b = 0; b < am->mNumBones; ++b) own[bone_node(am->mBones[b])] = 1;
    // An unskinned mesh moves with its node; a skinned one binds its unweighted vertices to it.
    if (am->mNumBones == 0 || has_unweighted_vertex(am)) own[in.node] = 1;
  }
  for (unsigned a = 0; a < scene->mNumAnimations; ++a)
    for (unsigned c = 0; c < scene->mAnimations[a]->mNumChannels; ++c) {
      const auto it = sn.by_name.find(scene->mAnimations[a]->mChannels[c]->mNodeName.C_Str());
      if (it != sn.by_name.end()) animated[it->second] = 1;
    }
  for (size_t i = n; i-- > 0;)  // pre-order: children come after their parents
    if ((own[i] || above[i]) && sn.parent[i] >= 0) above[sn.parent[i]] = 1;
  std::vector<char> keep(n, 0);
  for (size_t i = 0; i < n; ++i)
    keep[i] = own[i] || (above[i] && (animated[i] || !is_similarity(to_matrix(sn.nodes[i]->mTransformation))));
  for (size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    Eigen::Matrix4d folded = Eigen::Matrix4d::Identity();
    int p = sn.parent[i];
    for (; p >= 0 && !keep[p]; p = sn.parent[p]) folded = to_matrix(sn.nodes[p]->mTransformation) * folded;
    Joint j;
    j.name = sn.nodes[i]->mName.C_Str();
    j.parent = p < 0 ? -1 : joints_of_node_[p].front();
    j.rest_local = to_matrix(sn.nodes[i]->mTransformation);
    if (p != sn.parent[i]) j.rest_local = folded * j.rest_local;  // untouched otherwise, bit for bit
    j.inverse_bind = sn.global[i].inverse();
    folded_above_[i] = folded;
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
