#pragma once
/** \file ModFrameFoldOverT.hh */

#include "OpenMeshSkinned/Collapse/FoldOver.hh"
#include "OpenMeshSkinned/Deform/ExampleFrames.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <algorithm>
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
    surviving_faces(Base::mesh(), ci.v0, ci.v1, ring_);
    // Endpoint placement: only v0's faces move (to v1's position).
    ring_.erase(std::remove_if(ring_.begin(), ring_.end(), [&](const RingFace& f) { return f[0] != ci.v0.idx(); }),
                ring_.end());
    const int v1 = ci.v1.idx();
    const bool fold = folds_in_any_pose(
        ring_, int(frames_.size()), [this](int v, int j) { return frames_[j][v]; },
        [this, v1](int j) { return frames_[j][v1]; }, min_cos_);
    return float(fold ? Base::ILLEGAL_COLLAPSE : Base::LEGAL_COLLAPSE);
  }

private:
  double min_cos_ = 0.0;
  std::vector<FramePoints> frames_;
  std::vector<RingFace> ring_;
};

}  // namespace OpenMeshSkinned
