#pragma once
/** \file ModFrameQuadricT.hh */

#include "OpenMeshSkinned/Deform/ExampleFrames.hh"

#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>

namespace OpenMeshSkinned {

/** Priority module: the error of a collapse summed over the example poses, each pose with its own
 *  Garland-Heckbert quadrics (area-weighted planes of the posed faces) evaluated at the surviving vertex's
 *  posed position. It is the skinned quadric's idea without weights to solve: the vertex's trajectory
 *  over the frames is fixed (the survivor keeps its own: halfedge collapse, endpoint placement), so the
 *  error of a trajectory is the sum of one quadric per frame. It needs no skeleton: the poses may be
 *  morph-target frames (a vertex animation) or skinned poses, morph offsets and skin applied.
 *
 *  Memory: one quadric (10 doubles) per vertex and example pose.
 *
 *  \code
 *  OpenMeshSkinned::ModFrameQuadricT<Mesh>::Handle hq;
 *  dec.add(hq);   // after setting example_poses(mesh)
 *  \endcode
 */
template <typename MeshT>
class ModFrameQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModFrameQuadricT, MeshT, FrameQuadric);
  using Quadric = OpenMesh::Geometry::QuadricT<double>;

  explicit ModFrameQuadricT(MeshT& mesh) : Base(mesh, false) {}

  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }

  void initialize() override {
    const MeshT& mesh = Base::mesh();
    frames_ = example_frame_points(mesh);
    P_ = frames_.size();
    q_.assign(mesh.n_vertices() * P_, Quadric(0.0, 0.0, 0.0, 0.0));
    for (auto fh : mesh.faces()) {
      auto fv = mesh.cfv_iter(fh);
      const int a = (fv++)->idx(), b = (fv++)->idx(), c = fv->idx();
      for (size_t t = 0; t < P_; ++t) {
        const Quadric q = area_plane_quadric<Quadric>(frames_[t][a], frames_[t][b], frames_[t][c]);
        q_[a * P_ + t] += q, q_[b * P_ + t] += q, q_[c * P_ + t] += q;
      }
    }
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const size_t v0 = ci.v0.idx(), v1 = ci.v1.idx();
    double e = 0.0;
    for (size_t t = 0; t < P_; ++t) {
      Quadric q = q_[v0 * P_ + t];
      q += q_[v1 * P_ + t];
      const Eigen::Vector3d& p = frames_[t][v1];
      e += q(OpenMesh::Vec3d(p.x(), p.y(), p.z()));
    }
    e = std::max(e, 0.0);
    if (e > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    return float(std::min<double>(e, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    const size_t v0 = ci.v0.idx(), v1 = ci.v1.idx();
    for (size_t t = 0; t < P_; ++t) q_[v1 * P_ + t] += q_[v0 * P_ + t];
  }

private:
  double max_err_ = DBL_MAX;
  std::vector<FramePoints> frames_;
  size_t P_ = 0;
  std::vector<Quadric> q_;
};

}  // namespace OpenMeshSkinned
