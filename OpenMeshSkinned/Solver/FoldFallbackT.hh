#pragma once
/** \file FoldFallbackT.hh
 *  Where a collapse whose solved placement folds a face may put the merged vertex instead.
 *
 *  The fold check (ModSkinnedFoldOverT) asks whether a placement turns a remaining face by more than its
 *  limit in any example pose (flips()). With fallback placements on, a collapse whose solved placement
 *  folds is offered at the cheapest of the midpoint and the endpoints (with the solved skin, or an
 *  endpoint's own) that folds nothing, priced by the same error (choose()); that choice then stands for
 *  that collapse until another collapse is priced or made.
 */

#include "OpenMeshSkinned/Collapse/FoldOver.hh"
#include "OpenMeshSkinned/Solver/EdgeAnswersT.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class FoldFallbackT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;
  using Placements = std::array<std::pair<Eigen::Vector3d, Influences>, 5>;

  FoldFallbackT(Mesh& mesh, const PoseCacheT<Mesh>& poses, EdgeAnswersT<Mesh>& answers)
      : mesh_(mesh), poses_(poses), answers_(answers) {}

  /** Whether collapsing \p ci, with the merged vertex at \p rest with skin \p w, turns any remaining face
   *  around it (only those at \p only_faces_at, when given) by more than acos(min_cos), or makes it
   *  degenerate, in any pose. */
  bool flips(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w, double min_cos,
             VertexHandle only_faces_at = VertexHandle()) const {
    surviving_faces(mesh_, ci.v0, ci.v1, ring_faces_, only_faces_at);
    return folds_in_any_pose(
        ring_faces_, poses_.n_poses(), [this](int v, int j) { return poses_.posed_stored(v, j); },
        [&](int j) { return poses_.posed_point(rest, w, j); }, min_cos);
  }

  /// The answer a collapse of \p ci will use: the fallback chosen for it, or the solved one.
  const CollapseResult& placement(const CollapseInfo& ci) { return chosen_for(ci) ? chosen_ : answers_.solve(ci); }

  /// Where and with which skin the merged vertex will be if \p ci is collapsed now.
  void placement_of(const CollapseInfo& ci, Eigen::Vector3d& rest, Influences& w) {
    if (answers_.settings().placement) {
      const CollapseResult& r = placement(ci);
      if (r.valid) {
        rest = r.position;
        w = r.weights;
        return;
      }
    }
    rest = to_eigen(mesh_.point(ci.v1));
    w = mesh_.property(poses_.influences(), ci.v1);
  }

  /** Chooses, for a collapse whose solved placement folds, the cheapest placement that turns no face by
   *  more than acos(\p min_cos) in any pose. False when every one folds, or when a module's own cost model
   *  places vertices and cannot price another placement (EdgeModelT::error_at). */
  bool choose(const CollapseInfo& ci, double min_cos) {
    chosen_valid_ = false;
    const SolverSettings& s = answers_.settings();
    if (!s.placement) return false;
    const CollapseResult& solved = answers_.solve(ci);
    if (!solved.valid) return false;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [p, w] : placements_to_try(ci, solved)) {
      if (w.size() > s.max_influences || flips(ci, p, w, min_cos)) continue;
      CollapseResult r;
      r.position = p;
      r.weights = w;
      if (!answers_.model())
        r.error = error_at(ci, p, w);
      else if (!answers_.model()->error_at(ci.v0, ci.v1, p, w, r.error))
        return chosen_valid_ = false;
      r.area = solved.area;
      r.valid = true;
      if (s.priority(r) < best) {
        best = s.priority(r);
        chosen_ = r;
        chosen_valid_ = true;
      }
    }
    chosen_v0_ = ci.v0;
    chosen_v1_ = ci.v1;
    return chosen_valid_;
  }
  /// Whether choose() found a placement for \p ci that still stands.
  bool chosen_for(const CollapseInfo& ci) const { return chosen_valid_ && chosen_v0_ == ci.v0 && chosen_v1_ == ci.v1; }
  const CollapseResult& chosen() const { return chosen_; }
  /// Drops the fallback chosen last: the next question about a collapse is about its solved placement.
  void forget() { chosen_valid_ = false; }

  /// The skinned quadric's error of collapsing \p ci with the merged vertex at \p rest with skin \p w: the
  /// endpoints' summed quadric of each pose at the vertex posed there, and their normal quadrics at \p rest.
  double error_at(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w) const {
    double e = 0.0;
    for (int j = 0; j < poses_.n_poses(); ++j) {
      PoseQuadric q = poses_.quadric(ci.v0, j);
      poses_.add_quadric(ci.v1, j, q);
      e += q(poses_.posed_point(rest, w, j));
    }
    const double nw = answers_.settings().normal_weight;
    if (const PoseQuadric* n0 = poses_.normal_quadric(ci.v0); n0 && nw > 0.0)
      e += nw * ((*n0)(rest) + (*poses_.normal_quadric(ci.v1))(rest));
    return std::max(e, 0.0);
  }

  /// Where a collapse may put the merged vertex when its solved placement folds: v1, the midpoint and v0
  /// with the solved skin, then v1 and v0 as they are.
  Placements placements_to_try(const CollapseInfo& ci, const CollapseResult& solved) const {
    const Eigen::Vector3d p0 = to_eigen(mesh_.point(ci.v0)), p1 = to_eigen(mesh_.point(ci.v1));
    const auto h_inf = poses_.influences();
    return {{{p1, solved.weights},
             {Eigen::Vector3d(0.5 * (p0 + p1)), solved.weights},
             {p0, solved.weights},
             {p1, mesh_.property(h_inf, ci.v1)},
             {p0, mesh_.property(h_inf, ci.v0)}}};
  }

private:
  Mesh& mesh_;
  const PoseCacheT<Mesh>& poses_;
  EdgeAnswersT<Mesh>& answers_;
  bool chosen_valid_ = false;  // choose()'s answer, for the collapse chosen_v0_ -> chosen_v1_
  VertexHandle chosen_v0_, chosen_v1_;
  CollapseResult chosen_;
  mutable std::vector<RingFace> ring_faces_;
};

}  // namespace OpenMeshSkinned
