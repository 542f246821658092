#pragma once
/** \file CollapseSolverT.hh
 *  The mesh side of the one solve per candidate edge that all OpenMeshSkinned decimater modules share.
 *
 *  For an edge it fills an EdgeProblem (the endpoints' summed per-pose quadrics, their joints' transforms,
 *  positions and skins) and hands it to the mesh-free kernel (SkinnedQuadricSolve.hh). The answer depends
 *  only on the two endpoints, so it is cached per edge and reused until either endpoint changes (vertex
 *  version stamps): DecimaterT asks for every edge around a collapse again, and most of those did not
 *  change. At a collapse it applies the answer: position, skin, per-pose quadrics, corner UVs and colours, morph
 * offsets.
 *
 *  The solver lives in the named mesh property "m:omsk_collapse_solver" (shared_solver()), so the modules
 *  find it and work alone or in any combination; its settings are gathered from the modules attached to
 *  it. How it relies on DecimaterT's call order is written down in SolverModuleT.hh.
 */

#include "OpenMeshSkinned/Decimater/CornerTransferT.hh"
#include "OpenMeshSkinned/Decimater/DriverHints.hh"
#include "OpenMeshSkinned/Decimater/FoldOver.hh"
#include "OpenMeshSkinned/Decimater/MorphTransferT.hh"
#include "OpenMeshSkinned/Solver/EdgeCache.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"
#include "OpenMeshSkinned/Solver/SolveAhead.hh"
#include "OpenMeshSkinned/Solver/SolverSettings.hh"
#include "OpenMeshSkinned/Solver/StaleVerdictsT.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace OpenMeshSkinned {

struct CollapseSolverStats {
  size_t requests = 0;    ///< times a module asked for an edge
  size_t solves = 0;      ///< edges actually solved
  size_t cache_hits = 0;  ///< answered from the cache
  size_t collapses = 0;
  size_t placement_fallbacks = 0;  ///< collapses whose solved position was stale and was replaced
  size_t forced_flips = 0;         ///< collapses DecimaterT made although every placement flips a face
  size_t deferred = 0;             ///< vertices held back until DecimaterT re-asked them (stale verdicts)
  size_t fold_fallbacks = 0;       ///< collapses made at a fallback placement: the solved one folded (fold_fallback)
  WeightSolverStats weights;
};

/** A cost model other than the skinned quadric that places the merged vertex (e.g. the rest-pose
 *  quadric); the solver then caches and applies its answers. */
template <typename Mesh>
class EdgeModelT {
public:
  virtual ~EdgeModelT() = default;
  virtual void solve_edge(typename Mesh::VertexHandle a, typename Mesh::VertexHandle b, CollapseResult& out) = 0;
  /// Whether an answer also depends on the faces around the edge (then a collapse makes the answers of
  /// every edge around the surviving vertex's ring stale, not only of the edges at that vertex).
  virtual bool ring_dependent() const { return false; }
  /// The error of merging \p a and \p b at \p rest with skin \p w, in solve_edge()'s units; false when the
  /// model can price only its own placement (the fold check's fallback placements are then not offered).
  virtual bool error_at(typename Mesh::VertexHandle /*a*/, typename Mesh::VertexHandle /*b*/,
                        const Eigen::Vector3d& /*rest*/, const Influences& /*w*/, double& /*error*/) {
    return false;
  }
};

/// What a module attached to the solver asks of it (SolverModuleT implements it).
template <typename Mesh>
class SolverClientT {
public:
  virtual ~SolverClientT() = default;
  /// Adds this module's wishes to \p s.
  virtual void contribute(SolverSettings& s) const = 0;
  /// A placing module's own cost model, replacing the skinned quadric; null for the others.
  virtual EdgeModelT<Mesh>* edge_model() { return nullptr; }
  /// Once per collapse, when the solver has applied it (v1 placed and posed), before it re-judges the
  /// verdicts DecimaterT stored near v1: a module keeping state per face updates it here.
  virtual void collapse_applied(const OpenMesh::Decimater::CollapseInfoT<Mesh>&) {}
  /// Whether this module would now refuse a collapse it accepted when DecimaterT priced it (asked for the
  /// collapses stored near v1 after each collapse, with SolverSettings::recheck_stale; see StaleVerdictsT).
  virtual bool now_refuses(const OpenMesh::Decimater::CollapseInfoT<Mesh>&) { return false; }
};

template <typename Mesh>
class CollapseSolverT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  explicit CollapseSolverT(Mesh& mesh) : mesh_(mesh), poses_(mesh), corners_(mesh), morph_(mesh), stale_(mesh) {}

  // ---- settings -----------------------------------------------------------------------------------------

  const SolverSettings& settings() const { return settings_; }
  /// Sets everything at once (a solver used without modules); attached modules overwrite it when they change.
  void set_settings(const SolverSettings& s) {
    const bool same = s.same_answers(settings_);
    settings_ = s;
    if (!same) invalidate_cache();
  }
  int max_influences() const { return settings_.max_influences; }
  /// Replaces the skinned quadric as the source of placements and errors (nullptr restores it).
  void set_edge_model(EdgeModelT<Mesh>* model) {
    const bool same = model == model_;
    model_ = model;
    if (!same) invalidate_cache();
  }
  /// Forgets every cached edge answer (a setting or a module's cost model changed).
  void invalidate_cache() {
    cache_.invalidate();
    // The slots are resized at the next solve, not here: modules detaching one by one at the end of a
    // run would otherwise widen them while everything else is still held.
    resize_cache_ = prepared_ && cache_.capacity() != answer_capacity();
  }

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
   *  calls it from initialize(); only the first call of a decimation does the work. */
  void prepare() {
    checks_at_pop_ = checks_at_pop(mesh_);
    if (prepared_) return;
    if (skeleton(mesh_).size() > EdgeCache::kMaxJoints)
      throw std::length_error("the skinned solver handles skeletons of at most " +
                              std::to_string(EdgeCache::kMaxJoints) + " joints; this one has " +
                              std::to_string(skeleton(mesh_).size()));
    poses_.build(threads_);
    h_inf_ = poses_.influences();
    cache_.reset(mesh_.n_edges(), mesh_.n_vertices(), answer_capacity());
    resize_cache_ = false;
    corners_.prepare();
    stale_.prepare();
    prepared_ = true;
    solved_ahead_ = false;
  }
  bool prepared() const { return prepared_; }

  /// Threads for solving all edges ahead of the first pricing (default: the hardware's; 1 = none started).
  void set_threads(int n) { threads_ = std::max(1, n); }
  int threads() const { return threads_; }

  int n_poses() const { return poses_.n_poses(); }
  const Pose& pose(int j) const { return poses_.pose(j); }
  /// Vertex \p v as it is, posed in example pose \p j.
  Eigen::Vector3d posed(VertexHandle v, int j) const { return poses_.posed(v, j); }
  /// For a module that calls posed() all the time: keep the posed positions in doubles as well (24 bytes
  /// more per vertex and pose) instead of computing each. Before prepare().
  void keep_exact_posed() { poses_.set_keep_exact(true); }
  /// A rest position with a skin, posed in example pose \p j (as a merged vertex would be).
  Eigen::Vector3d posed_point(const Eigen::Vector3d& rest, const Influences& w, int j) const {
    return poses_.posed_point(rest, w, j);
  }
  PoseQuadric& quadric(VertexHandle v, int j) { return poses_.quadric(v, j); }
  const PoseQuadric& quadric(VertexHandle v, int j) const { return poses_.quadric(v, j); }

  // ---- solving ------------------------------------------------------------------------------------------

  /// The most influences an answer can have: the cap, unless a module's own cost model answers.
  int answer_capacity() const { return model_ ? Influences::kCapacity : settings_.max_influences; }
  /// Sizes the cache's slots for answer_capacity() after the settings changed; not while a worker solves
  /// ahead into them (until then, answers too wide are solved again when asked).
  void resize_cache() {
    if (!resize_cache_ || ahead_) return;
    cache_.set_capacity(answer_capacity());
    resize_cache_ = false;
  }

  /// The optimal merged vertex for the edge of \p ci, from the cache when its endpoints did not change.
  /// The reference is valid until the next call.
  const CollapseResult& solve(const CollapseInfo& ci) {
    ++stats_.requests;
    const int e = mesh_.edge_handle(ci.v0v1).idx();
    const int a = std::min(ci.v0.idx(), ci.v1.idx()), b = std::max(ci.v0.idx(), ci.v1.idx());
    if (ahead_) ahead_->settle(e);
    resize_cache();
    if (cache_.find(e, a, b, answer_)) {
      ++stats_.cache_hits;
      return answer_;
    }
    ++stats_.solves;
    if (model_) {
      model_->solve_edge(VertexHandle(a), VertexHandle(b), answer_);
    } else {
      load_problem(VertexHandle(a), VertexHandle(b), problem_);
      solve_collapse(problem_, settings_, weights_, answer_);
    }
    cache_.store(e, a, b, answer_);
    return answer_;
  }

  /** Solves every live edge not in the cache on \p threads threads, ahead of a driver's first pricing pass
   *  (BatchPricing). Each answer depends only on its edge's endpoints, so nothing depends on the thread
   *  count. Not with a module's own cost model, which need not be safe to call concurrently. */
  void solve_all_edges(int threads) {
    if (!prepared_) return;
    solved_ahead_ = true;
    resize_cache();
    if (model_ || !settings_.placement) return;
    std::vector<int> todo;
    for (auto eh : mesh_.edges()) {
      const auto h = mesh_.halfedge_handle(eh, 0);
      const int a = mesh_.from_vertex_handle(h).idx(), b = mesh_.to_vertex_handle(h).idx();
      if (!cache_.has(eh.idx(), std::min(a, b), std::max(a, b))) todo.push_back(eh.idx());
    }
    threads = std::max(1, std::min<int>(threads, static_cast<int>(todo.size() / 256) + 1));
    std::vector<WeightSolverStats> counts(threads);
    std::atomic<size_t> next{0};
    auto work = [&](int t) {
      EdgeProblem problem;
      CollapseResult answer;
      WeightSolver weights;
      weights.set_regularization(weights_.regularization());
      weights.set_force_ceres(weights_.force_ceres());
      constexpr size_t kBlock = 64;
      for (size_t i0 = next.fetch_add(kBlock); i0 < todo.size(); i0 = next.fetch_add(kBlock))
        for (size_t i = i0; i < std::min(todo.size(), i0 + kBlock); ++i) {
          const auto h = mesh_.halfedge_handle(typename Mesh::EdgeHandle(todo[i]), 0);
          const int a = mesh_.from_vertex_handle(h).idx(), b = mesh_.to_vertex_handle(h).idx();
          const VertexHandle va(std::min(a, b)), vb(std::max(a, b));
          load_problem(va, vb, problem);
          solve_collapse(problem, settings_, weights, answer);
          cache_.store(todo[i], va.idx(), vb.idx(), answer);
        }
      counts[t] = weights.stats();
    };
    run_on_threads(threads, work);
    stats_.solves += todo.size();
    for (const auto& c : counts) batch_weights_ += c;
  }

  /** Under a driver that asks binary modules at pop time, with \p threads > 1: a worker thread solves the
   *  edges each collapse makes stale while the driver goes on (SolveAhead.hh; the answers are the same).
   *  Not with a module's own cost model, which need not be safe to call concurrently. */
  void start_solving_ahead(int threads) {
    if (threads > 1 && checks_at_pop_ && prepared_ && !model_ && settings_.placement && !ahead_)
      ahead_ = std::make_unique<SolveAhead>(cache_, mesh_.n_edges(), settings_, weights_);
  }
  void stop_solving_ahead() {
    if (!ahead_) return;
    ahead_->stop();
    batch_weights_ += ahead_->worker_stats();
    ahead_.reset();
  }

  /** Whether collapsing \p ci, with the merged vertex at \p rest with skin \p w, turns any remaining face
   *  around it by more than acos(min_cos), or makes it degenerate, in any pose. */
  bool flips(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w, double min_cos,
             VertexHandle only_faces_at = VertexHandle()) const {
    surviving_faces(mesh_, ci.v0, ci.v1, ring_faces_, only_faces_at);
    return folds_in_any_pose(
        ring_faces_, poses_.n_poses(), [this](int v, int j) { return poses_.posed_stored(v, j); },
        [&](int j) { return poses_.posed_point(rest, w, j); }, min_cos);
  }

  /// Where and with which skin the merged vertex will be if \p ci is collapsed now.
  void placement_of(const CollapseInfo& ci, Eigen::Vector3d& rest, Influences& w) {
    if (settings_.placement) {
      const CollapseResult& r = placement(ci);
      if (r.valid) {
        rest = r.position;
        w = r.weights;
        return;
      }
    }
    rest = to_eigen(mesh_.point(ci.v1));
    w = mesh_.property(h_inf_, ci.v1);
  }

  /// The answer a collapse of \p ci will use: the fallback chosen for it (choose_fallback_placement), or the
  /// solved one.
  const CollapseResult& placement(const CollapseInfo& ci) { return chosen_for(ci) ? chosen_ : solve(ci); }

  /** Chooses, for a collapse whose solved placement folds, the cheapest placement that turns no face by
   *  more than acos(\p min_cos) in any pose: the midpoint or an endpoint with the solved skin, or an
   *  endpoint with its own. The collapse of \p ci then uses it, until another collapse is priced or made.
   *  False when every one folds, or when a module's own cost model places vertices and cannot price
   *  another placement (EdgeModelT::error_at). */
  bool choose_fallback_placement(const CollapseInfo& ci, double min_cos) {
    chosen_valid_ = false;
    if (!settings_.placement) return false;
    const CollapseResult& solved = solve(ci);
    if (!solved.valid) return false;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [p, w] : placements_to_try(ci, solved)) {
      if (w.size() > settings_.max_influences || flips(ci, p, w, min_cos)) continue;
      CollapseResult r;
      r.position = p;
      r.weights = w;
      if (!model_)
        r.error = error_at(ci, p, w);
      else if (!model_->error_at(ci.v0, ci.v1, p, w, r.error))
        return chosen_valid_ = false;
      r.area = solved.area;
      r.valid = true;
      if (settings_.priority(r) < best) {
        best = settings_.priority(r);
        chosen_ = r;
        chosen_valid_ = true;
      }
    }
    chosen_v0_ = ci.v0;
    chosen_v1_ = ci.v1;
    return chosen_valid_;
  }
  /// The skinned quadric's error of collapsing \p ci with the merged vertex at \p rest with skin \p w: the
  /// endpoints' summed quadric of each pose at the vertex posed there.
  double error_at(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w) const {
    double e = 0.0;
    for (int j = 0; j < poses_.n_poses(); ++j) {
      PoseQuadric q = poses_.quadric(ci.v0, j);
      q += poses_.quadric(ci.v1, j);
      e += q(poses_.posed_point(rest, w, j));
    }
    return std::max(e, 0.0);
  }
  /// Drops the fallback chosen last: the next question about a collapse is about its solved placement.
  void forget_chosen_placement() { chosen_valid_ = false; }

  // ---- pricing (see SolverModuleT.hh) ----------------------------------------------------------------------

  // Under a driver that asks binary modules at pop time (checks_at_pop) verdicts are never stale and
  // the priority module is asked alone: the sweep bookkeeping, the shortcut and the deferral are off.

  /// Every module calls this first in collapse_priority (SolverModuleT does). The first call of a
  /// decimation solves every edge ahead on threads() threads: every edge is priced first anyway.
  void begin_pricing(const CollapseInfo& ci) {
    if (!solved_ahead_) solve_all_edges(threads_);
    if (!chosen_for(ci)) chosen_valid_ = false;
    if (!checks_at_pop_) stale_.begin_pricing(ci);
  }
  /// The priority module reports a collapse that every binary module accepted, with its cost.
  void note_legal_priority(const CollapseInfo& ci, double error) {
    if (!checks_at_pop_) stale_.note_legal(ci, error);
  }
  /// Whether \p ci cannot win over a legal collapse already priced for the same v0 (its checks can be skipped).
  bool cannot_win(const CollapseInfo& ci) {
    return !checks_at_pop_ && settings_.placement && stale_.has_legal(ci.v0) &&
           settings_.priority(solve(ci)) >= stale_.best_error();
  }

  // ---- collapse (every module forwards its pre/postprocess; the first call does the work) ----------------

  void begin_collapse(const CollapseInfo& ci) {
    if (pending_) return;
    pending_ = true;
    stale_.begin_collapse(ci);
    pending_result_.valid = false;
    corners_.record(ci.v0, ci.v1);
    morph_.record(ci.v0, ci.v1);
    if (!settings_.placement) return;
    if (chosen_for(ci)) {
      pending_result_ = chosen_;
      ++stats_.fold_fallbacks;
    } else {
      pending_result_ = solve(ci);
    }
    chosen_valid_ = false;
    if (settings_.fold_check && !checks_at_pop_ && pending_result_.valid &&
        flips(ci, pending_result_.position, pending_result_.weights, settings_.fold_cos))
      replace_stale_placement(ci);
  }

  void end_collapse(const CollapseInfo& ci) {
    if (!pending_) return;
    pending_ = false;
    ++stats_.collapses;
    const VertexHandle v0 = ci.v0, v1 = ci.v1;
    poses_.merge_quadrics(v0, v1);
    if (settings_.placement && pending_result_.valid) {
      const Eigen::Vector3d& p = pending_result_.position;
      mesh_.set_point(v1, typename Mesh::Point(p.x(), p.y(), p.z()));
      mesh_.property(h_inf_, v1) = pending_result_.weights;
      poses_.update(v1);
      if (mesh_.has_face_normals())
        for (auto fh : mesh_.vf_range(v1)) mesh_.set_normal(fh, mesh_.calc_face_normal(fh));
    } else if (mesh_.property(h_inf_, v1).size() > settings_.max_influences) {
      reduce_vertex(v1);
    }
    // Moved or not, v1's corners that came from v0 carry v0's UVs and colours: re-interpolate all of them.
    corners_.apply(v1);
    morph_.apply(v1);
    cache_.touch(v1.idx());
    cache_.touch(v0.idx());
    if (model_ && model_->ring_dependent())
      for (auto v : mesh_.vv_range(v1)) cache_.touch(v.idx());
    if (ahead_) {
      // The neighbours' quadrics are read below one after another: ask for all of them at once.
      for (auto v : mesh_.vv_range(v1)) poses_.prefetch_quadrics(v);
      for (auto h : mesh_.voh_range(v1)) {
        const int a = std::min(v1.idx(), mesh_.to_vertex_handle(h).idx());
        const int b = std::max(v1.idx(), mesh_.to_vertex_handle(h).idx());
        const int e = mesh_.edge_handle(h).idx();
        if (EdgeProblem* p = ahead_->reserve(e, a, b, cache_.stamp(a), cache_.stamp(b))) {
          // The support is found on the worker: the skins are copied, not merged, on the mesh thread.
          load_poses(VertexHandle(a), VertexHandle(b), *p);
          ahead_->submit(mesh_.property(h_inf_, VertexHandle(a)), mesh_.property(h_inf_, VertexHandle(b)));
        }
      }
    }
    for (auto* c : clients_) c->collapse_applied(ci);
    // Moved or not, v1 now holds v0's faces: verdicts around it may be stale. (After the stamps: the
    // re-checks must not reuse answers cached for v1 as it was.)
    if (settings_.placement && (settings_.fold_check || settings_.recheck_stale) && !checks_at_pop_)
      stats_.deferred += stale_.defer_around(v1, [this, v1](const CollapseInfo& zc) {
        if (settings_.fold_check) {
          Eigen::Vector3d rest;
          Influences w;
          placement_of(zc, rest, w);
          // zc was judged fold-free when priced and after every collapse since: only the faces at v1 can
          // have changed, unless it ends at v1 (its placement moved with v1), its placement depends on the
          // ring, or its verdict may have been for a fallback placement (placement_of gives the solved one).
          const bool all_faces = zc.v1 == v1 || settings_.fold_fallback || (model_ && model_->ring_dependent());
          if (flips(zc, rest, w, settings_.fold_cos, all_faces ? VertexHandle() : v1)) return true;
        }
        if (settings_.recheck_stale)
          for (auto* c : clients_)
            if (c->now_refuses(zc)) return true;
        return false;
      });
  }

  /// Unlocks every vertex the solver deferred (see StaleVerdictsT); modules call it when done.
  void release_deferred() { stale_.release(); }

  /** Reduces every vertex with more than max_influences() bones by the weight solve on its own quadrics
   *  at its own position (not by plain truncation). Returns how many vertices changed. */
  size_t reduce_input_influences() {
    size_t changed = 0;
    for (auto vh : mesh_.vertices())
      if (mesh_.property(h_inf_, vh).size() > settings_.max_influences) {
        reduce_vertex(vh);
        ++changed;
      }
    return changed;
  }

  CollapseSolverStats stats() const {
    CollapseSolverStats s = stats_;
    s.weights = weights_.stats();
    s.weights += batch_weights_;
    return s;
  }
  WeightSolver& weight_solver() { return weights_; }

private:
  void load_problem(VertexHandle va, VertexHandle vb, EdgeProblem& problem) const {
    problem.set_skins(mesh_.property(h_inf_, va), mesh_.property(h_inf_, vb));
    load_poses(va, vb, problem);
  }
  // All of a problem but its skins: the endpoints' summed quadrics and positions, and the poses.
  void load_poses(VertexHandle va, VertexHandle vb, EdgeProblem& problem) const {
    problem.use_poses(&poses_.poses());
    problem.resize(poses_.n_poses());
    for (int j = 0; j < poses_.n_poses(); ++j) {
      problem.quadric[j] = poses_.quadric(va, j);
      if (vb != va) problem.quadric[j] += poses_.quadric(vb, j);
    }
    problem.pa = to_eigen(mesh_.point(va));
    problem.pb = to_eigen(mesh_.point(vb));
  }

  // DecimaterT does not re-ask binary modules when it pops a collapse, and it re-asks only the vertices
  // around v0 after each collapse, not those around a moved v1: the verdict may be stale. Place the
  // vertex where it flips nothing now, trying the solved weights at the endpoints and the midpoint,
  // then v1 as it is.
  // With fold_fallback the cheapest that folds nothing, as the collapse was priced.
  void replace_stale_placement(const CollapseInfo& ci) {
    if (settings_.fold_fallback && choose_fallback_placement(ci, settings_.fold_cos)) {
      pending_result_ = chosen_;
      chosen_valid_ = false;
      ++stats_.fold_fallbacks;
      return;
    }
    ++stats_.placement_fallbacks;
    for (const auto& [p, w] : placements_to_try(ci, pending_result_)) {
      if (w.size() <= settings_.max_influences && !flips(ci, p, w, settings_.fold_cos)) {
        pending_result_.position = p;
        pending_result_.weights = w;
        return;
      }
    }
    pending_result_.valid = false;
    ++stats_.forced_flips;
  }

  // Where a collapse may put the merged vertex when its solved placement folds: v1, the midpoint and v0
  // with the solved skin, then v1 and v0 as they are.
  std::array<std::pair<Eigen::Vector3d, Influences>, 5> placements_to_try(const CollapseInfo& ci,
                                                                          const CollapseResult& solved) const {
    const Eigen::Vector3d p0 = to_eigen(mesh_.point(ci.v0)), p1 = to_eigen(mesh_.point(ci.v1));
    return {{{p1, solved.weights},
             {Eigen::Vector3d(0.5 * (p0 + p1)), solved.weights},
             {p0, solved.weights},
             {p1, mesh_.property(h_inf_, ci.v1)},
             {p0, mesh_.property(h_inf_, ci.v0)}}};
  }
  bool chosen_for(const CollapseInfo& ci) const { return chosen_valid_ && chosen_v0_ == ci.v0 && chosen_v1_ == ci.v1; }

  // A vertex with too many bones: weight solve on its own quadrics at its own position, capped.
  void reduce_vertex(VertexHandle vh) {
    load_problem(vh, vh, problem_);
    mesh_.property(h_inf_, vh) = reduce_influences(problem_, settings_, weights_);
    poses_.update(vh);
    cache_.touch(vh.idx());
  }

  Mesh& mesh_;
  SolverSettings settings_;
  EdgeModelT<Mesh>* model_ = nullptr;
  std::vector<SolverClientT<Mesh>*> clients_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  PoseCacheT<Mesh> poses_;
  CornerTransferT<Mesh> corners_;
  MorphTransferT<Mesh> morph_;
  StaleVerdictsT<Mesh> stale_;
  EdgeCache cache_;
  bool resize_cache_ = false;
  std::unique_ptr<SolveAhead> ahead_;  // after cache_: its worker stops before the cache it writes into goes
  bool prepared_ = false;
  bool checks_at_pop_ = false;
  bool solved_ahead_ = false;
  int threads_ = std::max(1u, std::thread::hardware_concurrency());
  bool pending_ = false;
  CollapseResult pending_result_;
  bool chosen_valid_ = false;  // choose_fallback_placement's answer, for the collapse chosen_v0_ -> chosen_v1_
  VertexHandle chosen_v0_, chosen_v1_;
  CollapseResult chosen_;
  CollapseResult answer_;  // what solve() returns
  EdgeProblem problem_;    // reused: no allocation per solve once grown
  mutable std::vector<RingFace> ring_faces_;
  WeightSolver weights_;
  WeightSolverStats batch_weights_;  // solve_all_edges()'s workers' counts
  CollapseSolverStats stats_;
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
