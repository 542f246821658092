#pragma once
/** \file SolverModuleT.hh
 *  The base of every OpenMeshSkinned decimater module: attaches the module to the mesh's shared
 *  CollapseSolverT, forwards the decimater's calls to it, and lets the module own its settings.
 *
 *  What the shared solver assumes of OpenMesh's DecimaterT (pinned by tests/test_decimater_contract.cc):
 *  1. collapse_priority() asks the binary modules first, in the order they were added, and the priority
 *     module last, only when every binary module accepted: so the priority module's report of a legal
 *     collapse (note_legal_priority) is a collapse DecimaterT may store.
 *  2. A vertex's outgoing halfedges are priced in a row (heap_vertex), and DecimaterT keeps the cheapest
 *     legal one, comparing float priorities, strictly smaller wins: the solver's record of a sweep.
 *  3. preprocess_collapse() and postprocess_collapse() reach every module once per collapse, binary
 *     modules first: the first call does the shared work, the others see it done.
 *  4. After a collapse DecimaterT re-prices only v0's former neighbours; it skips locked vertices when it
 *     pops and prices them (the deferral of StaleVerdictsT.hh).
 *  Under LazyDecimaterT (checks_at_pop(), DriverHints.hh) only 3 holds: binary modules are asked right
 *  before each collapse, the priority module alone when pricing, and the solver drops 1, 2 and 4.
 */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <memory>

namespace OpenMeshSkinned {

template <typename MeshT>
class SolverModuleT : public OpenMesh::Decimater::ModBaseT<MeshT>,
                      protected SolverClientT<MeshT>,
                      public BatchPricing,
                      public EndpointPriority,
                      public EdgePriority,
                      public PriceAfterChecks {
  using ModBase = OpenMesh::Decimater::ModBaseT<MeshT>;

public:
  using CollapseInfo = typename ModBase::CollapseInfo;

  SolverModuleT(MeshT& mesh, bool is_binary) : ModBase(mesh, is_binary), solver_(shared_solver(mesh)) {
    solver_->attach(this);
  }
  ~SolverModuleT() override {
    solver_->release_deferred();
    if (solver_->detach(this)) release_shared_solver(ModBase::mesh());
  }

  void initialize() override { solver_->prepare(); }

  float collapse_priority(const CollapseInfo& ci) final {
    solver_->begin_pricing(ci);
    return price(ci);
  }
  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override { solver_->end_collapse(ci); }
  /// Solves every edge ahead on \p threads threads (LazyDecimaterT calls it; the modules share one solver,
  /// so the second module's call finds everything done).
  void price_all_edges(int threads) override {
    solver_->solve_all_edges(threads);
    solver_->start_solving_ahead(threads);
  }
  void end_of_run() override { solver_->stop_solving_ahead(); }
  bool prices_after_checks() const override { return solver_->settings().fold_fallback; }

  /// The shared solver: settings and counters (solves, cache hits, Ceres calls, forced flips).
  CollapseSolverT<MeshT>& solver() { return *solver_; }

protected:
  /// The module's collapse_priority().
  virtual float price(const CollapseInfo& ci) = 0;
  /// Call after changing anything contribute() reports.
  void settings_changed() { solver_->refresh_settings(); }
  void contribute(SolverSettings&) const override {}

private:
  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
};

}  // namespace OpenMeshSkinned
