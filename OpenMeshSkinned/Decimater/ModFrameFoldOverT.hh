#pragma once
/** \file ModFrameFoldOverT.hh */

#include "OpenMeshSkinned/Deform/ExampleFrames.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cmath>

namespace OpenMeshSkinned {

/** Binary module: refuses a halfedge collapse (endpoint placement) that turns a face around v0 by more
 *  than set_max_angle() degrees (default 90) in any example pose, or leaves it without area there: the
 *  fold-over check of the deformation modules (ModFrameQuadricT, ModDeformationWeightedQuadricT), which,
 *  unlike ModSkinnedFoldOverT, need no skinned solver and see morph-target frames.
 *
 *  \code
 *  OpenMeshSkinned::ModFrameFoldOverT<Mesh>::Handle hf;
 *  dec.add(hf);
 *  \endcode
 */
template <typename MeshT>
class ModFrameFoldOverT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModFrameFoldOverT, MeshT, FrameFoldOver);

  explicit ModFrameFoldOverT(MeshT& mesh) : Base(mesh, true) {}

  void set_max_angle(double deg) { min_cos_ = std::cos(deg * M_PI / 180.0); }
  double max_angle() const { return std::acos(min_cos_) * 180.0 / M_PI; }

  void initialize() override { frames_ = example_frame_points(Base::mesh()); }

  float collapse_priority(const CollapseInfo& ci) override {
    const MeshT& mesh = Base::mesh();
    for (auto fh : mesh.vf_range(ci.v0)) {
      if (fh == ci.fl || fh == ci.fr) continue;
      int v[3], k = 0, at = -1;
      for (auto vh : mesh.fv_range(fh)) {
        if (vh == ci.v0) at = k;
        v[k++] = vh.idx();
      }
      for (const FramePoints& p : frames_) {
        const Eigen::Vector3d n0 = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]);
        Eigen::Vector3d q[3] = {p[v[0]], p[v[1]], p[v[2]]};
        q[at] = p[ci.v1.idx()];
        const Eigen::Vector3d n1 = (q[1] - q[0]).cross(q[2] - q[0]);
        const double l0 = n0.norm(), l1 = n1.norm();
        if (!(l1 > 0.0)) return float(Base::ILLEGAL_COLLAPSE);
        if (l0 > 0.0 && n0.dot(n1) < min_cos_ * l0 * l1) return float(Base::ILLEGAL_COLLAPSE);
      }
    }
    return float(Base::LEGAL_COLLAPSE);
  }

private:
  double min_cos_ = 0.0;
  std::vector<FramePoints> frames_;
};

}  // namespace OpenMeshSkinned
