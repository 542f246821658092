#pragma once
/** \file EdgeAnswersT.hh
 *  The shared solver's answers for edges: where the merged vertex goes, with which skin, at what error.
 *
 *  For an edge it fills an EdgeProblem (the endpoints' summed per-pose quadrics, their joints' transforms,
 *  positions and skins) and hands it to the mesh-free kernel (SkinnedQuadricSolve.hh), or asks a module's
 *  own cost model (EdgeModelT). An answer depends only on the two endpoints, so it is cached per edge and
 *  reused until either endpoint changes (vertex version stamps, EdgeCache.hh): DecimaterT asks for every
 *  edge around a collapse again, and most of those did not change. Answers are computed ahead, for every
 *  edge on several threads before the first pricing, and with a worker thread for the edges each collapse
 *  makes stale (SolveAhead.hh); neither changes an answer.
 */

#include "OpenMeshSkinned/Solver/EdgeCache.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"
#include "OpenMeshSkinned/Solver/SolveAhead.hh"
#include "OpenMeshSkinned/Solver/SolverClient.hh"
#include "OpenMeshSkinned/Solver/SolverSettings.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class EdgeAnswersT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  EdgeAnswersT(Mesh& mesh, PoseCacheT<Mesh>& poses) : mesh_(mesh), poses_(poses) {}

  const SolverSettings& settings() const { return settings_; }
  /// Forgets the cached answers when \p s answers differently.
  void set_settings(const SolverSettings& s) {
    const bool same = s.same_answers(settings_);
    settings_ = s;
    if (!same) invalidate();
  }
  EdgeModelT<Mesh>* model() const { return model_; }
  /// Replaces the skinned quadric as the source of answers (nullptr restores it).
  void set_model(EdgeModelT<Mesh>* model) {
    const bool same = model == model_;
    model_ = model;
    if (!same) invalidate();
  }
  /// Whether a collapse also changes the answers of the edges around the surviving vertex's ring.
  bool ring_dependent() const { return model_ && model_->ring_dependent(); }

  /// Forgets every cached answer.
  void invalidate() {
    cache_.invalidate();
    // The slots are resized at the next solve, not here: modules detaching one by one at the end of a
    // run would otherwise widen them while everything else is still held.
    resize_cache_ = prepared_ && cache_.capacity() != answer_capacity();
  }

  /// After the pose tables are built: one empty slot per edge.
  void prepare() {
    h_inf_ = poses_.influences();
    cache_.reset(mesh_.n_edges(), mesh_.n_vertices(), answer_capacity());
    resize_cache_ = false;
    prepared_ = true;
    solved_ahead_ = false;
  }
  bool prepared() const { return prepared_; }
  /// Whether solve_all_edges() ran in this decimation.
  bool solved_all() const { return solved_ahead_; }

  /// The most influences an answer can have: the cap, unless a module's own cost model answers.
  int answer_capacity() const { return model_ ? Influences::kCapacity : settings_.max_influences; }

  /// The answer for the edge of \p ci, from the cache when its endpoints did not change. The reference is
  /// valid until the next call.
  const CollapseResult& solve(const CollapseInfo& ci) {
    ++requests_;
    const int e = mesh_.edge_handle(ci.v0v1).idx();
    const int a = std::min(ci.v0.idx(), ci.v1.idx()), b = std::max(ci.v0.idx(), ci.v1.idx());
    if (ahead_) ahead_->settle(e);
    resize_cache();
    if (cache_.find(e, a, b, answer_)) {
      ++cache_hits_;
      return answer_;
    }
    ++solves_;
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
    solves_ += todo.size();
    for (const auto& c : counts) batch_weights_ += c;
  }

  /** With \p threads > 1, a worker thread solves the edges each collapse makes stale while the driver goes
   *  on (SolveAhead.hh). Only under a driver that asks binary modules at pop time: DecimaterT asks for the
   *  answers right after the collapse, before a worker could give them. Not with a module's own cost
   *  model, which need not be safe to call concurrently. */
  void start_solving_ahead(int threads) {
    if (threads > 1 && prepared_ && !model_ && settings_.placement && !ahead_)
      ahead_ = std::make_unique<SolveAhead>(
          cache_, mesh_.n_edges(), settings_, weights_,
          [this](int a, int b, EdgeProblem& problem) { load_problem(VertexHandle(a), VertexHandle(b), problem); });
  }
  void stop_solving_ahead() {
    if (!ahead_) return;
    ahead_->stop();
    batch_weights_ += ahead_->worker_stats();
    ahead_.reset();
  }

  /// \p v changed (position, skin or quadrics): its edges' answers are stale.
  void vertex_changed(VertexHandle v) { cache_.touch(v.idx()); }
  /// Before \p v's position, skin or quadrics are written: the worker, if any, no longer reads them.
  void will_change(VertexHandle v) {
    if (ahead_) ahead_->release_vertex(v.idx());
  }

  /// After \p v0 was collapsed into \p v1: the answers that changed are stale, and the worker (if any)
  /// starts on v1's edges.
  void collapsed(VertexHandle v0, VertexHandle v1) {
    cache_.touch(v1.idx());
    cache_.touch(v0.idx());
    if (ring_dependent())
      for (auto v : mesh_.vv_range(v1)) cache_.touch(v.idx());
    if (!ahead_) return;
    for (auto h : mesh_.voh_range(v1)) {
      const int a = std::min(v1.idx(), mesh_.to_vertex_handle(h).idx());
      const int b = std::max(v1.idx(), mesh_.to_vertex_handle(h).idx());
      ahead_->submit(mesh_.edge_handle(h).idx(), a, b, cache_.stamp(a), cache_.stamp(b));
    }
  }

  /// The skin of \p vh reduced to the cap by the weight solve on its own quadrics at its own position.
  Influences reduced_skin(VertexHandle vh) {
    load_problem(vh, vh, problem_);
    return reduce_influences(problem_, settings_, weights_);
  }

  WeightSolver& weight_solver() { return weights_; }
  /// Adds the requests, solves, cache hits and weight-solve counts to \p s.
  void add_counts(CollapseSolverStats& s) const {
    s.requests += requests_;
    s.solves += solves_;
    s.cache_hits += cache_hits_;
    s.weights += weights_.stats();
    s.weights += batch_weights_;
  }

private:
  // Sizes the cache's slots for answer_capacity() after the settings changed; not while a worker solves
  // ahead into them (until then, answers too wide are solved again when asked).
  void resize_cache() {
    if (!resize_cache_ || ahead_) return;
    cache_.set_capacity(answer_capacity());
    resize_cache_ = false;
  }
  void load_problem(VertexHandle va, VertexHandle vb, EdgeProblem& problem) const {
    problem.set_skins(mesh_.property(h_inf_, va), mesh_.property(h_inf_, vb));
    problem.use_poses(&poses_.poses());
    problem.resize(poses_.n_poses());
    for (int j = 0; j < poses_.n_poses(); ++j) {
      problem.quadric[j] = PoseQuadric{};
      poses_.add_quadric(va, j, problem.quadric[j]);
      if (vb != va) poses_.add_quadric(vb, j, problem.quadric[j]);
    }
    problem.pa = to_eigen(mesh_.point(va));
    problem.pb = to_eigen(mesh_.point(vb));
    problem.attribute = PoseQuadric{};
    if (const PoseQuadric* na = poses_.normal_quadric(va); na && settings_.normal_weight > 0.0) {
      problem.attribute = *na;
      if (vb != va) problem.attribute += *poses_.normal_quadric(vb);
      for (double& x : problem.attribute.q) x *= settings_.normal_weight;
    }
  }

  Mesh& mesh_;
  PoseCacheT<Mesh>& poses_;
  SolverSettings settings_;
  EdgeModelT<Mesh>* model_ = nullptr;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  EdgeCache cache_;
  bool resize_cache_ = false;
  std::unique_ptr<SolveAhead> ahead_;  // after cache_: its worker stops before the cache it writes into goes
  bool prepared_ = false;
  bool solved_ahead_ = false;
  CollapseResult answer_;  // what solve() returns
  EdgeProblem problem_;    // reused: no allocation per solve once grown
  WeightSolver weights_;
  WeightSolverStats batch_weights_;  // the workers' counts
  size_t requests_ = 0, solves_ = 0, cache_hits_ = 0;
};

}  // namespace OpenMeshSkinned
