#pragma once
/** \file SolveAhead.hh
 *  A worker thread that solves edges while the decimation goes on.
 *
 *  Under a lazy driver a collapse makes the answers of the surviving vertex's edges stale, and each is
 *  solved again when its candidate is popped: a third of a decimation, on the driver's thread. The mesh
 *  thread submits those edges right after the collapse; the worker fills each one's problem (the loader:
 *  the endpoints' per-pose quadrics, positions and skins) and solves it into the edge cache while the
 *  driver goes on. Filling the problems was a large part of the driver's time per collapse: the
 *  neighbours' quadrics are seldom in cache.
 *
 *  Two rules keep the threads apart:
 *  - before the mesh thread reads or writes an edge's cache entry it settles the edge: a job the worker has
 *    not started is cancelled (the mesh thread then solves the edge itself if the cache has no answer),
 *    one it is on is waited for;
 *  - before it writes what the loader reads of a vertex (a collapse's surviving vertex), it releases the
 *    vertex: jobs that would read it are cancelled, the one being filled or solved is waited for.
 *  An answer depends only on its problem, so the decimation is the same with or without the worker; only
 *  where the work is done changes.
 *
 *  Jobs wait in a ring; a job the worker has not reached when its slot comes round again is cancelled.
 *  The mesh thread waits only for a job the worker is on (at most one solve).
 */

#include "OpenMeshSkinned/Solver/EdgeCache.hh"
#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <thread>

namespace OpenMeshSkinned {

class SolveAhead {
public:
  /// Fills \p problem for the edge between vertices \p a < \p b (called on the worker).
  using Loader = std::function<void(int a, int b, EdgeProblem& problem)>;
  /// Solves into \p cache (of \p n_edges edges) with \p settings and a weight solver set up as \p like, the
  /// problems filled by \p load.
  SolveAhead(EdgeCache& cache, size_t n_edges, const SolveSettings& settings, const WeightSolver& like, Loader load);
  /// Jobs that can wait at once. The worker seldom lags by more than a few (512 slots left no fewer
  /// solves to the mesh thread than 128).
  static constexpr size_t kRing = 128;
  ~SolveAhead();
  SolveAhead(const SolveAhead&) = delete;
  SolveAhead& operator=(const SolveAhead&) = delete;

  /// Queues edge \p e between vertices \p a < \p b at their stamps \p sa, \p sb. False when the worker is
  /// busy with that ring slot or edge (nothing queued). Mesh thread only.
  bool submit(int e, int a, int b, uint32_t sa, uint32_t sb);

  /// Makes edge \p e's cache entry the mesh thread's again (see the file comment). Mesh thread only.
  void settle(int e);
  /// Before the mesh thread writes what the loader reads of vertex \p v (see the file comment).
  void release_vertex(int v);

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
    EdgeProblem problem;
  };
  void work();

  EdgeCache& cache_;
  const SolveSettings settings_;
  const Loader load_;
  std::unique_ptr<Job[]> ring_;
  // Per ring slot, the vertices its last job reads: the mesh thread's own copy, scanned by release_vertex()
  // without touching the jobs themselves.
  std::array<std::array<int, 2>, kRing> reads_;
  std::unique_ptr<std::atomic<uint32_t>[]> mark_;
  std::atomic<size_t> head_{0};  // jobs submitted
  std::atomic<bool> stop_{false};
  std::atomic<size_t> solved_{0};
  uint32_t tickets_ = 0;
  WeightSolver weights_;   // the worker's
  CollapseResult answer_;  // the worker's, copied into the cache
  std::thread worker_;
};

}  // namespace OpenMeshSkinned
