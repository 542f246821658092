#pragma once
/** \file ModDeformationWeightedQuadricT.hh */

#include "OpenMeshSkinned/Deform/ExampleFrames.hh"

#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>
#include <numeric>

namespace OpenMeshSkinned {

/** Priority module: Garland-Heckbert quadrics in the rest shape, each face's plane weighted by how much
 *  the mesh deforms around it over the example poses (the deformation-analysis report, eq. 5-8). Needs no
 *  skeleton: the example poses may be morph-target frames (a vertex animation) or skinned poses.
 *
 *  A face's importance is the average, over its edges, of the largest squared Frobenius difference of the
 *  deformation gradients on the two sides (face_importance()). The report's formula that puts it into the
 *  quadric is lost in the extracted text; what it says around it is that faces that move little are
 *  simplified first and the quadric keeps its properties. A plain product would let rigid parts (importance
 *  0) collapse for free and lose their shape, so the face's quadric here is its area-weighted plane quadric
 *  times 1 + s * importance / mean importance, s = set_importance_scale() (default 1; 0 gives plain
 *  area-weighted QEM).
 *
 *  Halfedge collapses with endpoint placement, as OpenMesh's ModQuadricT: the surviving vertex keeps its
 *  position, morph offsets and skin, so its trajectory over the animation is one of the input's.
 *
 *  \code
 *  OpenMeshSkinned::ModDeformationWeightedQuadricT<Mesh>::Handle hq;
 *  dec.add(hq);   // after setting example_poses(mesh): the frames to analyse
 *  \endcode
 */
template <typename MeshT>
class ModDeformationWeightedQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModDeformationWeightedQuadricT, MeshT, DeformationWeightedQuadric);
  using Quadric = OpenMesh::Geometry::QuadricT<double>;

  explicit ModDeformationWeightedQuadricT(MeshT& mesh) : Base(mesh, false) {}

  void set_importance_scale(double s) { scale_ = s; }
  double importance_scale() const { return scale_; }
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }
  /// Each face's importance (by face index), as computed by initialize().
  const std::vector<double>& importance() const { return importance_; }

  void initialize() override {
    const MeshT& mesh = Base::mesh();
    const FramePoints rest = rest_points(mesh);
    importance_ = face_importance(mesh, rest, example_frame_points(mesh));
    double sum = 0.0;
    size_t n = 0;
    for (double w : importance_)
      if (w > 0.0) sum += w, ++n;
    const double mean = n > 0 ? sum / n : 1.0;
    q_.assign(mesh.n_vertices(), Quadric(0.0, 0.0, 0.0, 0.0));
    for (auto fh : mesh.faces()) {
      auto fv = mesh.cfv_iter(fh);
      const auto a = *fv++, b = *fv++, c = *fv;
      Quadric q = area_plane_quadric<Quadric>(rest[a.idx()], rest[b.idx()], rest[c.idx()]);
      q *= 1.0 + scale_ * importance_[fh.idx()] / mean;
      q_[a.idx()] += q, q_[b.idx()] += q, q_[c.idx()] += q;
    }
  }

  float collapse_priority(const CollapseInfo& ci) override {
    Quadric q = q_[ci.v0.idx()];
    q += q_[ci.v1.idx()];
    const auto& p = ci.p1;
    const double e = std::max(0.0, q(OpenMesh::Vec3d(p[0], p[1], p[2])));
    if (e > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    return float(std::min<double>(e, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override { q_[ci.v1.idx()] += q_[ci.v0.idx()]; }

private:
  double scale_ = 1.0;
  double max_err_ = DBL_MAX;
  std::vector<double> importance_;
  std::vector<Quadric> q_;
};

}  // namespace OpenMeshSkinned
