#pragma once
/** \file ModSkinnedFoldOverT.hh */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cmath>

namespace OpenMeshSkinned {

/** Binary module: refuses a collapse if any face around it would turn its normal by more than the
 *  maximum angle (degrees, default 90 as DeCoro & Rusinkiewicz), or become degenerate, in ANY example
 *  pose. The check uses the merged vertex where it will really be: the solver's position and weights
 *  when ModSkinnedQuadricT places vertices, v1 as it is otherwise.
 *
 *  DecimaterT asks binary modules when it prices a collapse, not when it executes it, and re-prices only
 *  the vertices around v0; a placing priority module moves v1 and can make a stored verdict wrong. The
 *  shared solver therefore re-checks the stored collapses near v1 after each collapse and sets the vertex
 *  status "locked" on those that would now fold, until the decimater re-prices them (it skips locked v0s).
 *  These locks are released when the modules are destroyed or by release_deferred(); vertices the user
 *  locked are never touched. What still slips through is counted in solver().stats().forced_flips.
 *
 *  \code
 *  OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle hf;
 *  dec.add(hf);
 *  dec.module(hf).set_max_angle(60.0);
 *  \endcode
 */
template <typename MeshT>
class ModSkinnedFoldOverT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModSkinnedFoldOverT, MeshT, SkinnedFoldOver);

  explicit ModSkinnedFoldOverT(MeshT& mesh) : Base(mesh, true) {
    solver_ = shared_solver(mesh, owns_property_);
    set_max_angle(90.0);
  }
  ~ModSkinnedFoldOverT() override {
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(Base::mesh());
  }

  void initialize() override { solver_->prepare(); }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    // Not the cheapest legal collapse from v0 anyway: the decimater will not pick it, skip the check.
    if (solver_->cannot_win(ci)) return float(Base::LEGAL_COLLAPSE);
    Eigen::Vector3d rest;
    Influences w;
    solver_->placement_of(ci, rest, w);
    return solver_->flips(ci, rest, w, min_cos_) ? float(Base::ILLEGAL_COLLAPSE) : float(Base::LEGAL_COLLAPSE);
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override { solver_->end_collapse(ci); }

  /// Unlocks the vertices held back from the last decimate call (see CollapseSolverT); call between
  /// successive decimate calls on the same decimater, e.g. when building a LOD chain.
  void release_deferred() { solver_->release_deferred(); }

  /// Largest allowed rotation of a face normal by one collapse, in degrees, in any pose (0..180].
  void set_max_angle(double deg) {
    max_angle_deg_ = deg;
    update();
  }
  double max_angle() const { return max_angle_deg_; }

  void set_error_tolerance_factor(double factor) override {
    if (factor >= 0.0 && factor <= 1.0) {
      Base::error_tolerance_factor_ = factor;
      update();
    }
  }

  /// The shared solver: settings and counters (forced_flips, deferred).
  CollapseSolverT<MeshT>& solver() { return *solver_; }

private:
  void update() {
    const double rad = max_angle_deg_ * Base::error_tolerance_factor_ * M_PI / 180.0;
    min_cos_ = std::cos(rad);
    solver_->set_fold_over_angle(rad);
  }

  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
  bool owns_property_ = false;
  double max_angle_deg_ = 90.0;
  double min_cos_ = 0.0;
};

}  // namespace OpenMeshSkinned
