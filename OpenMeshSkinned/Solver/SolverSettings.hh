#pragma once
/** \file SolverSettings.hh
 *  What the shared collapse solver does, as one value. With modules attached it is gathered from them
 *  (SolverModuleT::contribute): each module owns its own parameters, and removing a module simply drops
 *  its contribution, never another module's.
 */

#include "OpenMeshSkinned/Solver/AreaPrice.hh"
#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {

struct SolverSettings : SolveSettings {
  /// Whether the merged vertex takes the solved position and weights (a placing priority module asks for
  /// it). Off, a collapse is OpenMesh's plain halfedge collapse: v1 keeps its position and skin.
  bool placement = false;
  /// Whether placements are checked for fold-overs at collapse time (ModSkinnedFoldOverT asks for it).
  bool fold_check = false;
  /// Smallest allowed cosine between a face's normals before and after a collapse, in every pose.
  double fold_cos = 0.0;
  /// Whether a collapse whose solved placement folds may be made at the cheapest placement that folds
  /// nothing instead: the midpoint or an endpoint (ModSkinnedFoldOverT::set_fallback_placement).
  bool fold_fallback = false;
  /// Whether a module other than the fold check re-judges DecimaterT's stored verdicts near v1 after each
  /// collapse (SolverClientT::now_refuses; ModDeviationBoundT asks for it).
  bool recheck_stale = false;
  /// Collapses are priced by error / area^area_exponent (ModSkinnedQuadricT::set_area_exponent): 0 is the
  /// energy itself, 1 a mean squared distance.
  double area_exponent = 0.0;
  /// Below this area a collapse is priced per area whatever the exponent (ModSkinnedQuadricT::set_area_floor).
  double area_floor = 0.0;

  /// The priority of a solved collapse: its error over a power of the area it stands for.
  double priority(const CollapseResult& r) const { return area_price(r.error, r.area, area_exponent, area_floor); }

  /// Whether two settings give the same edge answers (the edge cache survives a change of the others).
  bool same_answers(const SolverSettings& o) const {
    return max_influences == o.max_influences && strategy == o.strategy && max_iterations == o.max_iterations &&
           tolerance == o.tolerance && normal_weight == o.normal_weight;
  }
};

}  // namespace OpenMeshSkinned
