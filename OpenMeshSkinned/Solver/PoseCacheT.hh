#pragma once
/** \file PoseCacheT.hh
 *  Per vertex and example pose: the posed position and the Garland-Heckbert quadric of the posed faces.
 *  Stored vertex-major (a vertex's poses side by side), as the solve reads them.
 */

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"

#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class PoseCacheT {
public:
  using VertexHandle = typename Mesh::VertexHandle;

  explicit PoseCacheT(Mesh& mesh) : mesh_(mesh) {}

  /// Reads the example poses ("m:skin_poses"; the bind pose when there are none) and fills both tables
  /// from the mesh as it is now.
  void build() {
    h_inf_ = influences_handle(mesh_);
    poses_ = example_poses(mesh_);
    if (poses_.empty()) poses_.push_back(Pose::identity(skeleton(mesh_).size()));
    P_ = static_cast<int>(poses_.size());
    const size_t nv = mesh_.n_vertices();
    posed_.assign(nv * P_, Eigen::Vector3d::Zero());
    quadric_.assign(nv * P_, PoseQuadric{});
    for (auto vh : mesh_.vertices()) update(vh);
    accumulate_quadrics(
        mesh_, P_, [this](VertexHandle v, int j) { return posed(v, j); },
        [this](VertexHandle v, int j) -> PoseQuadric& { return quadric(v, j); });
  }

  int n_poses() const { return P_; }
  const Pose& pose(int j) const { return poses_[j]; }
  OpenMesh::VPropHandleT<Influences> influences() const { return h_inf_; }

  const Eigen::Vector3d& posed(int v, int j) const { return posed_[v * P_ + j]; }
  const Eigen::Vector3d& posed(VertexHandle v, int j) const { return posed(v.idx(), j); }
  PoseQuadric& quadric(VertexHandle v, int j) { return quadric_[v.idx() * P_ + j]; }
  const PoseQuadric& quadric(VertexHandle v, int j) const { return quadric_[v.idx() * P_ + j]; }

  /// A rest position with a skin, posed in pose \p j.
  Eigen::Vector3d posed_point(const Eigen::Vector3d& rest, const Influences& w, int j) const {
    return skin_point(rest, w, poses_[j]);
  }

  /// Re-poses \p v after its rest position or skin changed.
  void update(VertexHandle v) {
    const Eigen::Vector3d rest = to_eigen(mesh_.point(v));
    const Influences& w = mesh_.property(h_inf_, v);
    for (int j = 0; j < P_; ++j) posed_[v.idx() * P_ + j] = skin_point(rest, w, poses_[j]);
  }

  /// \p into now stands for \p from's faces too.
  void merge_quadrics(VertexHandle from, VertexHandle into) {
    for (int j = 0; j < P_; ++j) quadric(into, j) += quadric(from, j);
  }

private:
  Mesh& mesh_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  std::vector<Pose> poses_;
  int P_ = 0;
  std::vector<Eigen::Vector3d> posed_;
  std::vector<PoseQuadric> quadric_;
};

}  // namespace OpenMeshSkinned
