#pragma once
/** \file StaleVerdictPolicyT.hh
 *  The shared solver's policy under OpenMesh's DecimaterT, which prices a collapse with the binary modules
 *  once and acts on the stored verdict later (SolverModuleT.hh lists what it assumes of that driver).
 *
 *  - Pricing: the cheapest legal collapse of each vertex's sweep is remembered (StaleVerdictsT), so that
 *    a binary module may skip its checks on a collapse that cannot win.
 *  - At a collapse: the placement is checked for folds again, as the faces around it may have changed
 *    since it was priced; a folding one is replaced by the cheapest fallback placement (with fold
 *    fallbacks on) or the first of v1, the midpoint and v0 that folds nothing.
 *  - After a collapse: the stored collapses near v1 are re-judged (the fold check, and every module that
 *    asks for it: SolverClientT::now_refuses), and the vertices whose stored collapse would now be refused
 *    are locked until DecimaterT re-prices them (the deferral, StaleVerdictsT).
 */

#include "OpenMeshSkinned/Solver/DriverPolicyT.hh"
#include "OpenMeshSkinned/Solver/FoldFallbackT.hh"
#include "OpenMeshSkinned/Solver/SolverClient.hh"
#include "OpenMeshSkinned/Solver/StaleVerdictsT.hh"

#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class StaleVerdictPolicyT : public DriverPolicyT<Mesh> {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  /// \p stats receives the placement fallbacks, forced flips and deferrals.
  StaleVerdictPolicyT(Mesh& mesh, EdgeAnswersT<Mesh>& answers, FoldFallbackT<Mesh>& fold,
                      const std::vector<SolverClientT<Mesh>*>& clients, CollapseSolverStats& stats)
      : stale_(mesh), answers_(answers), fold_(fold), clients_(clients), stats_(stats) {}

  bool checks_at_pop() const override { return false; }
  void prepare() override { stale_.prepare(); }

  void begin_pricing(const CollapseInfo& ci) override { stale_.begin_pricing(ci); }
  void note_legal(const CollapseInfo& ci, double error) override { stale_.note_legal(ci, error); }
  bool cannot_win(const CollapseInfo& ci) override {
    const SolverSettings& s = answers_.settings();
    return s.placement && stale_.has_legal(ci.v0) && s.priority(answers_.solve(ci)) >= stale_.best_error();
  }

  void before_collapse(const CollapseInfo& ci) override { stale_.begin_collapse(ci); }

  // DecimaterT does not re-ask binary modules when it pops a collapse, and it re-asks only the vertices
  // around v0 after each collapse, not those around a moved v1: the verdict may be stale.
  void check_placement(const CollapseInfo& ci, CollapseResult& pending) override {
    const SolverSettings& s = answers_.settings();
    if (!s.fold_check || !pending.valid || !fold_.flips(ci, pending.position, pending.weights, s.fold_cos)) return;
    // With fold fallbacks, the cheapest that folds nothing, as the collapse was priced.
    if (s.fold_fallback && fold_.choose(ci, s.fold_cos)) {
      pending = fold_.chosen();
      fold_.forget();
      ++stats_.fold_fallbacks;
      return;
    }
    ++stats_.placement_fallbacks;
    for (const auto& [p, w] : fold_.placements_to_try(ci, pending)) {
      if (w.size() <= s.max_influences && !fold_.flips(ci, p, w, s.fold_cos)) {
        pending.position = p;
        pending.weights = w;
        return;
      }
    }
    pending.valid = false;
    ++stats_.forced_flips;
  }

  // Moved or not, v1 now holds v0's faces: verdicts around it may be stale. (After the answers' stamps
  // moved on: the re-checks must not reuse answers cached for v1 as it was.)
  void after_collapse(VertexHandle v1) override {
    const SolverSettings& s = answers_.settings();
    if (!s.placement || !(s.fold_check || s.recheck_stale)) return;
    stats_.deferred += stale_.defer_around(v1, [this, v1, &s](const CollapseInfo& zc) {
      if (s.fold_check) {
        Eigen::Vector3d rest;
        Influences w;
        fold_.placement_of(zc, rest, w);
        // zc was judged fold-free when priced and after every collapse since: only the faces at v1 can
        // have changed, unless it ends at v1 (its placement moved with v1), its placement depends on the
        // ring, or its verdict may have been for a fallback placement (placement_of gives the solved one).
        const bool all_faces = zc.v1 == v1 || s.fold_fallback || answers_.ring_dependent();
        if (fold_.flips(zc, rest, w, s.fold_cos, all_faces ? VertexHandle() : v1)) return true;
      }
      if (s.recheck_stale)
        for (auto* c : clients_)
          if (c->now_refuses(zc)) return true;
      return false;
    });
  }

  void release() override { stale_.release(); }

private:
  StaleVerdictsT<Mesh> stale_;
  EdgeAnswersT<Mesh>& answers_;
  FoldFallbackT<Mesh>& fold_;
  const std::vector<SolverClientT<Mesh>*>& clients_;
  CollapseSolverStats& stats_;
};

}  // namespace OpenMeshSkinned
