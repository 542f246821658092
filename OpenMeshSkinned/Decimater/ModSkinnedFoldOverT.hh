#pragma once
/** \file ModSkinnedFoldOverT.hh */

#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"

#include <algorithm>

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
 *  Under LazyDecimaterT, which asks binary modules right before each collapse, none of this is needed
 *  and none of it happens.
 *
 *  \code
 *  OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle hf;
 *  dec.add(hf);
 *  dec.module(hf).set_max_angle(60.0);
 *  \endcode
 */
template <typename MeshT>
class ModSkinnedFoldOverT : public SolverModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModSkinnedFoldOverT, MeshT, SkinnedFoldOver);

  explicit ModSkinnedFoldOverT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, true) { update(); }

  /// Unlocks the vertices held back from the last decimate call (see StaleVerdictsT); call between
  /// successive decimate calls on the same decimater, e.g. when building a LOD chain.
  void release_deferred() { this->solver().release_deferred(); }

  /// Largest allowed rotation of a face normal by one collapse, in degrees, in any pose (0..180].
  void set_max_angle(double deg) {
    max_angle_deg_ = deg;
    update();
  }
  double max_angle() const { return max_angle_deg_; }

  /** When the solved placement of a collapse would fold, allow the collapse at the cheapest placement that
   *  folds nothing instead: the midpoint or an endpoint, with the solved skin or the endpoint's own. The
   *  collapse is then priced at that placement (LazyDecimaterT queues it again if that makes it no longer
   *  the cheapest). Off by default: such a collapse waits until its neighbourhood changes. With a placing
   *  priority module that can price another placement: the skinned quadric, the rest-pose and DeCoro's
   *  quadrics (not the triangle compactness); without one, v1 stays where it is. */
  void set_fallback_placement(bool on) {
    fallback_ = on;
    this->settings_changed();
  }
  bool fallback_placement() const { return fallback_; }

  void set_error_tolerance_factor(double factor) override {
    if (factor >= 0.0 && factor <= 1.0) {
      Base::error_tolerance_factor_ = factor;
      update();
    }
  }

protected:
  float price(const CollapseInfo& ci) override {
    // Not the cheapest legal collapse from v0 anyway: the decimater will not pick it, skip the check.
    auto& solver = this->solver();
    if (solver.cannot_win(ci)) return float(Base::LEGAL_COLLAPSE);
    solver.forget_chosen_placement();
    Eigen::Vector3d rest;
    Influences w;
    solver.placement_of(ci, rest, w);
    if (!solver.flips(ci, rest, w, min_cos_)) return float(Base::LEGAL_COLLAPSE);
    return fallback_ && solver.choose_fallback_placement(ci, min_cos_) ? float(Base::LEGAL_COLLAPSE)
                                                                       : float(Base::ILLEGAL_COLLAPSE);
  }
  void contribute(SolverSettings& s) const override {
    // With several fold-over modules the strictest wins.
    s.fold_cos = s.fold_check ? std::max(s.fold_cos, min_cos_) : min_cos_;
    s.fold_check = true;
    s.fold_fallback = s.fold_fallback || fallback_;
  }

private:
  void update() {
    min_cos_ = std::cos(max_angle_deg_ * Base::error_tolerance_factor_ * M_PI / 180.0);
    this->settings_changed();
  }

  double max_angle_deg_ = 90.0;
  double min_cos_ = 0.0;
  bool fallback_ = false;
};

}  // namespace OpenMeshSkinned
