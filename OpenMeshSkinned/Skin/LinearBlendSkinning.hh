#pragma once
/** \file LinearBlendSkinning.hh
 *  Linear blend skinning: p = sum_k w_k M_k v, for one vertex or the whole mesh.
 */

#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace OpenMeshSkinned {

/// The blended affine map sum_k w_k M_k of one vertex in one pose.
inline Affine3 blend(const Influences& inf, const Pose& pose) {
  Affine3 m = Affine3::Zero();
  for (const JointWeight& jw : inf) m += jw.weight * pose.joint[jw.joint];
  return m;
}

/// Skinned position of a rest-pose point with influences \p inf in \p pose.
inline Eigen::Vector3d skin_point(const Eigen::Vector3d& rest, const Influences& inf, const Pose& pose) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const JointWeight& jw : inf) p += jw.weight * (pose.joint[jw.joint] * rest.homogeneous());
  return p;
}

template <typename Point>
Eigen::Vector3d to_eigen(const Point& p) {
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

/// Poses one vertex at a time as glTF poses it: the pose's morph offsets first, then linear blend skinning.
/// A deleted vertex keeps its rest position.
template <typename Mesh>
class VertexPoser {
public:
  VertexPoser(const Mesh& mesh, const Pose& pose) : mesh_(mesh), pose_(pose), h_(influences_handle(mesh)) {
    morph_ = !pose.morph_weights.empty() && morph_deltas_handle(mesh, hd_);
  }
  Eigen::Vector3d operator()(typename Mesh::VertexHandle vh) const {
    Eigen::Vector3d rest = to_eigen(mesh_.point(vh));
    if (mesh_.status(vh).deleted()) return rest;
    if (morph_) rest = apply_morph(rest, mesh_.property(hd_, vh), pose_.morph_weights);
    return skin_point(rest, mesh_.property(h_, vh), pose_);
  }

private:
  const Mesh& mesh_;
  const Pose& pose_;
  OpenMesh::VPropHandleT<Influences> h_;
  OpenMesh::VPropHandleT<MorphDeltas> hd_;
  bool morph_ = false;
};

/// Posed positions of all vertices, indexed by vertex index (VertexPoser).
template <typename Mesh>
std::vector<Eigen::Vector3d> skin_positions(const Mesh& mesh, const Pose& pose) {
  const VertexPoser<Mesh> posed(mesh, pose);
  std::vector<Eigen::Vector3d> out(mesh.n_vertices());
  for (auto vh : mesh.all_vertices()) out[vh.idx()] = posed(vh);
  return out;
}

/// Posed unit face normals (indexed by face index; zero for deleted or degenerate faces).
template <typename Mesh>
std::vector<Eigen::Vector3d> skin_face_normals(const Mesh& mesh, const std::vector<Eigen::Vector3d>& posed) {
  std::vector<Eigen::Vector3d> out(mesh.n_faces(), Eigen::Vector3d::Zero());
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const Eigen::Vector3d& a = posed[(fv++)->idx()];
    const Eigen::Vector3d& b = posed[(fv++)->idx()];
    const Eigen::Vector3d& c = posed[fv->idx()];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len > 0.0) out[fh.idx()] = n / len;
  }
  return out;
}

}  // namespace OpenMeshSkinned
