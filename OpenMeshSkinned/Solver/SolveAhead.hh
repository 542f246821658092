#pragma once
/** \file SolveAhead.hh
 *  A worker thread that solves edges while the decimation goes on.
 *
 *  Under a lazy driver a collapse makes the answers of the surviving vertex's edges stale, and each is
 *  solved again when its candidate is popped: a third of a decimation, on the driver's thread. The mesh
 *  thread fills those edges' problems right after the collapse (it alone reads the mesh) and submits them;
 *  the worker solves them into the edge cache while the driver goes on. Before the mesh thread reads or
 *  writes an edge's cache entry it settles the edge: a job the worker has not started is cancelled (the
 *  mesh thread then solves the edge itself if the cache has no answer), one it is on is waited for. An
 *  answer depends only on its problem, so the decimation is the same with or without the worker; only
 *  where the work is done changes.
 *
 *  Problems wait in a ring; a job the worker has not reached when its slot comes round again is cancelled.
 *  The mesh thread waits only for an answer it needs that the worker is computing (at most one solve).
 */

#include "OpenMeshSkinned/Solver/EdgeCache.hh"
#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

namespace OpenMeshSkinned {

class SolveAhead {
public:
  /// Solves into \p cache (of \p n_edges edges) with \p settings and a weight solver set up as \p like.
  SolveAhead(EdgeCache& cache, size_t n_edges, const SolveSettings& settings, const WeightSolver& like);
  /// Jobs that can wait at once. The worker seldom lags by more than a few (512 slots left no fewer
  /// solves to the mesh thread than 128).
  static constexpr size_t kRing = 128;
  ~SolveAhead();
  SolveAhead(const SolveAhead&) = delete;
  SolveAhead& operator=(const SolveAhead&) = delete;

  /// The problem to fill for edge \p e between \p a < \p b at vertex stamps \p sa, \p sb, which submit()
  /// then hands to the worker; null when the worker is busy with that slot or edge (nothing to submit).
  /// Mesh thread only.
  EdgeProblem* reserve(int e, int a, int b, uint32_t sa, uint32_t sb);
  void submit();
  /// As submit(), for a problem filled but for its skins: the worker calls set_skins(\p wa, \p wb).
  void submit(const Influences& wa, const Influences& wb);

  /// Makes edge \p e's cache entry the mesh thread's again (see the file comment). Mesh thread only.
  void settle(int e);

  /// Stops the worker (jobs not started are dropped); worker_stats() is final afterwards.
  void stop();
  /// Edges the worker has solved so far.
  size_t solved() const { return solved_.load(std::memory_order_acquire); }
  /// The worker's weight-solve counts (after stop()).
  const WeightSolverStats& worker_stats() const { return weights_.stats(); }

private:
  // A slot of the ring: free, queued, or being read by the worker.
  enum Slot : int { kFree, kQueued, kRunning };
  // Per edge: the ticket of its last job (upper bits) and that job's state (two low bits).
  enum Mark : uint32_t { kNone = 0, kWaiting = 1, kSolving = 2, kSolved = 3 };
  struct Job {
    std::atomic<int> slot{kFree};
    int edge = -1, a = -1, b = -1;
    uint32_t sa = 0, sb = 0, ticket = 0;
    bool skins_to_set = false;
    Influences wa, wb;
    EdgeProblem problem;
  };
  void work();

  EdgeCache& cache_;
  const SolveSettings settings_;
  std::unique_ptr<Job[]> ring_;
  std::unique_ptr<std::atomic<uint32_t>[]> mark_;
  std::atomic<size_t> head_{0};  // jobs submitted
  std::atomic<bool> stop_{false};
  std::atomic<size_t> solved_{0};
  size_t reserved_ = 0;
  uint32_t tickets_ = 0;
  WeightSolver weights_;   // the worker's
  CollapseResult answer_;  // the worker's, copied into the cache
  std::thread worker_;
};

}  // namespace OpenMeshSkinned
