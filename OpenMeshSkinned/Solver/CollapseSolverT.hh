#pragma once
/** \file CollapseSolverT.hh
 *  The one solver per mesh that all OpenMeshSkinned decimater modules share: a coordinator over
 *  - the example poses' tables (PoseCacheT: per-vertex, per-pose quadrics and posed positions),
 *  - the edges' answers (EdgeAnswersT: the cache, the batch solve and the solve-ahead worker),
 *  - the fold check and its fallback placements (FoldFallbackT),
 *  - what a collapse does to the surviving vertex (CollapseApplierT),
 *  - and the policy of the driver it runs under (DriverPolicyT; under DecimaterT, StaleVerdictPolicyT).
 *
 *  The solver lives in the named mesh property "m:omsk_collapse_solver" (shared_solver()), so the modules
 *  find it and work alone or in any combination; its settings are gathered from the modules attached to
 *  it. How it relies on DecimaterT's call order is written down in SolverModuleT.hh.
 */

#include "OpenMeshSkinned/Collapse/DriverHints.hh"
#include "OpenMeshSkinned/Solver/CollapseApplierT.hh"
#include "OpenMeshSkinned/Solver/DriverPolicyT.hh"
#include "OpenMeshSkinned/Solver/EdgeAnswersT.hh"
#include "OpenMeshSkinned/Solver/FoldFallbackT.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"
#include "OpenMeshSkinned/Solver/SolverClient.hh"
#include "OpenMeshSkinned/Solver/SolverSettings.hh"
#include "OpenMeshSkinned/Solver/StaleVerdictPolicyT.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class CollapseSolverT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  explicit CollapseSolverT(Mesh& mesh)
      : mesh_(mesh),
        poses_(mesh),
        answers_(mesh, poses_),
        fold_(mesh, poses_, answers_),
        applier_(mesh, poses_, answers_),
        // Until a driver says otherwise (prepare()), DecimaterT's: a solver used on its own keeps its verdicts honest.
        policy_(std::make_unique<StaleVerdictPolicyT<Mesh>>(mesh, answers_, fold_, clients_, stats_)) {}

  // ---- settings -----------------------------------------------------------------------------------------

  const SolverSettings& settings() const { return answers_.settings(); }
  /// Sets everything at once (a solver used without modules); attached modules overwrite it when they change.
  void set_settings(const SolverSettings& s) { answers_.set_settings(s); }
  int max_influences() const { return settings().max_influences; }
  /// Replaces the skinned quadric as the source of placements and errors (nullptr restores it).
  void set_edge_model(EdgeModelT<Mesh>* model) { answers_.set_model(model); }
  /// Forgets every cached edge answer (a setting or a module's cost model changed).
  void invalidate_cache() { answers_.invalidate(); }

  void attach(SolverClientT<Mesh>* m) {
    clients_.push_back(m);
    refresh_settings();
  }
  /// Returns true when no module is left.
  bool detach(SolverClientT<Mesh>* m) {
    clients_.erase(std::remove(clients_.begin(), clients_.end(), m), clients_.end());
    refresh_settings();
    return clients_.empty();
  }
  /// Gathers the settings from the attached modules (they call it when one of theirs changes).
  void refresh_settings() {
    SolverSettings s;
    EdgeModelT<Mesh>* model = nullptr;
    for (auto* c : clients_) {
      c->contribute(s);
      if (!model) model = c->edge_model();
    }
    set_settings(s);
    set_edge_model(model);
  }

  // ---- lifetime -----------------------------------------------------------------------------------------

  /** Builds per-vertex, per-pose quadrics and posed positions from the mesh as it is now. Every module
   *  calls it from initialize(); only the first call of a decimation does the work. Throws
   *  std::invalid_argument when the mesh has no example poses (example_poses(): they are what the
   *  collapses are judged in; the bind pose alone must be asked for). */
  void prepare() {
    use_policy_of_driver();
    if (answers_.prepared()) return;
    if (skeleton(mesh_).size() > EdgeCache::kMaxJoints)
      throw std::length_error("the skinned solver handles skeletons of at most " +
                              std::to_string(EdgeCache::kMaxJoints) + " joints; this one has " +
                              std::to_string(skeleton(mesh_).size()));
    poses_.set_normal_quadrics(answers_.settings().normal_weight > 0.0);
    poses_.build(threads_);
    answers_.prepare();
    applier_.prepare();
    policy_->prepare();
  }
  bool prepared() const { return answers_.prepared(); }

  /// Threads for solving all edges ahead of the first pricing (default: the hardware's; 1 = none started).
  void set_threads(int n) { threads_ = std::max(1, n); }
  int threads() const { return threads_; }

  int n_poses() const { return poses_.n_poses(); }
  const Pose& pose(int j) const { return poses_.pose(j); }
  /// Vertex \p v as it is, posed in example pose \p j.
  Eigen::Vector3d posed(VertexHandle v, int j) const { return poses_.posed(v, j); }
  /// For a module that calls posed() all the time: keep the posed positions in doubles as well instead of
  /// computing each (a vertex-pose costs 24 bytes more). Before prepare().
  void keep_exact_posed() { poses_.set_keep_exact(true); }
  /// A rest position with a skin, posed in example pose \p j (as a merged vertex would be).
  Eigen::Vector3d posed_point(const Eigen::Vector3d& rest, const Influences& w, int j) const {
    return poses_.posed_point(rest, w, j);
  }
  PoseQuadric quadric(VertexHandle v, int j) const { return poses_.quadric(v, j); }

  // ---- solving (EdgeAnswersT) ------------------------------------------------------------------------------

  /// The optimal merged vertex for the edge of \p ci, from the cache when its endpoints did not change.
  /// The reference is valid until the next call.
  const CollapseResult& solve(const CollapseInfo& ci) { return answers_.solve(ci); }
  /// Solves every live edge not in the cache on \p threads threads, ahead of a driver's first pricing pass.
  void solve_all_edges(int threads) { answers_.solve_all_edges(threads); }
  /// Under a driver that asks binary modules at pop time, with \p threads > 1: a worker thread solves the
  /// edges each collapse makes stale while the driver goes on (the answers are the same).
  void start_solving_ahead(int threads) {
    if (policy_->checks_at_pop()) answers_.start_solving_ahead(threads);
  }
  void stop_solving_ahead() { answers_.stop_solving_ahead(); }

  // ---- the fold check's placements (FoldFallbackT) -------------------------------------------------------

  /// Whether collapsing \p ci with the merged vertex at \p rest with skin \p w folds a face in any pose.
  bool flips(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w, double min_cos,
             VertexHandle only_faces_at = VertexHandle()) const {
    return fold_.flips(ci, rest, w, min_cos, only_faces_at);
  }
  /// Where and with which skin the merged vertex will be if \p ci is collapsed now.
  void placement_of(const CollapseInfo& ci, Eigen::Vector3d& rest, Influences& w) { fold_.placement_of(ci, rest, w); }
  /// The answer a collapse of \p ci will use: the fallback chosen for it, or the solved one.
  const CollapseResult& placement(const CollapseInfo& ci) { return fold_.placement(ci); }
  /// Chooses the cheapest placement of \p ci that folds nothing; the collapse then uses it, until another
  /// collapse is priced or made (FoldFallbackT::choose).
  bool choose_fallback_placement(const CollapseInfo& ci, double min_cos) { return fold_.choose(ci, min_cos); }
  /// The skinned quadric's error of collapsing \p ci with the merged vertex at \p rest with skin \p w.
  double error_at(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w) const {
    return fold_.error_at(ci, rest, w);
  }
  /// Drops the fallback chosen last: the next question about a collapse is about its solved placement.
  void forget_chosen_placement() { fold_.forget(); }

  // ---- pricing (see SolverModuleT.hh) ----------------------------------------------------------------------

  /// Every module calls this first in collapse_priority (SolverModuleT does). The first call of a
  /// decimation solves every edge ahead on threads() threads: every edge is priced first anyway.
  void begin_pricing(const CollapseInfo& ci) {
    if (!answers_.solved_all()) answers_.solve_all_edges(threads_);
    if (!fold_.chosen_for(ci)) fold_.forget();
    policy_->begin_pricing(ci);
  }
  /// The priority module reports a collapse that every binary module accepted, with its cost.
  void note_legal_priority(const CollapseInfo& ci, double error) { policy_->note_legal(ci, error); }
  /// Whether \p ci cannot win over a legal collapse already priced for the same v0 (its checks can be skipped).
  bool cannot_win(const CollapseInfo& ci) { return policy_->cannot_win(ci); }

  // ---- collapse (every module forwards its pre/postprocess; the first call does the work) ----------------

  void begin_collapse(const CollapseInfo& ci) {
    if (pending_) return;
    pending_ = true;
    policy_->before_collapse(ci);
    pending_result_.valid = false;
    applier_.record(ci);
    if (!settings().placement) return;
    if (fold_.chosen_for(ci)) {
      pending_result_ = fold_.chosen();
      ++stats_.fold_fallbacks;
    } else {
      pending_result_ = answers_.solve(ci);
    }
    fold_.forget();
    policy_->check_placement(ci, pending_result_);
  }

  void end_collapse(const CollapseInfo& ci) {
    if (!pending_) return;
    pending_ = false;
    ++stats_.collapses;
    applier_.apply(ci, settings().placement && pending_result_.valid ? &pending_result_ : nullptr);
    for (auto* c : clients_) c->collapse_applied(ci);
    policy_->after_collapse(ci.v1);
  }

  /// Unlocks every vertex the solver deferred (StaleVerdictsT); modules call it when done. Under
  /// DecimaterT, call it between two decimations: a vertex still locked is never collapsed.
  void release_deferred() { policy_->release(); }

  /** Reduces every vertex with more than max_influences() bones by the weight solve on its own quadrics
   *  at its own position (not by plain truncation). Returns how many vertices changed. */
  size_t reduce_input_influences() { return applier_.reduce_input_influences(); }

  CollapseSolverStats stats() const {
    CollapseSolverStats s = stats_;
    answers_.add_counts(s);
    return s;
  }
  WeightSolver& weight_solver() { return answers_.weight_solver(); }

private:
  // The driver says which it is with a mesh property (DriverHints.hh) before the modules' initialize().
  void use_policy_of_driver() {
    const bool at_pop = checks_at_pop(mesh_);
    if (policy_->checks_at_pop() == at_pop) return;
    policy_->release();
    if (at_pop)
      policy_ = std::make_unique<DriverPolicyT<Mesh>>();
    else
      policy_ = std::make_unique<StaleVerdictPolicyT<Mesh>>(mesh_, answers_, fold_, clients_, stats_);
    if (answers_.prepared()) policy_->prepare();
  }

  Mesh& mesh_;
  std::vector<SolverClientT<Mesh>*> clients_;
  PoseCacheT<Mesh> poses_;
  EdgeAnswersT<Mesh> answers_;
  FoldFallbackT<Mesh> fold_;
  CollapseApplierT<Mesh> applier_;
  CollapseSolverStats stats_;  // before policy_, which counts into it
  std::unique_ptr<DriverPolicyT<Mesh>> policy_;
  int threads_ = std::max(1u, std::thread::hardware_concurrency());
  bool pending_ = false;
  CollapseResult pending_result_;
};

/// Name of the mesh property holding the shared solver.
inline constexpr const char* kSolverProperty = "m:omsk_collapse_solver";

/// The solver shared by all modules on \p mesh, created on first use.
template <typename Mesh>
std::shared_ptr<CollapseSolverT<Mesh>> shared_solver(Mesh& mesh) {
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> h;
  if (!mesh.get_property_handle(h, kSolverProperty)) mesh.add_property(h, kSolverProperty);
  auto& sp = mesh.property(h);
  if (!sp) sp = std::make_shared<CollapseSolverT<Mesh>>(mesh);
  return sp;
}

/// Removes the solver property and the solver's vertex marks (when the last module detaches).
template <typename Mesh>
void release_shared_solver(Mesh& mesh) {
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> h;
  if (mesh.get_property_handle(h, kSolverProperty)) mesh.remove_property(h);
  release_stale_marks(mesh);
}

}  // namespace OpenMeshSkinned
