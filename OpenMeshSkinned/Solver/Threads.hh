#pragma once
/** \file Threads.hh
 *  Fork and join of a few threads, for the solver's batch work (set-up, solving every edge ahead, the final
 *  fit's poses). Each caller shares the work out itself, so that its results do not depend on the count.
 */

#include <thread>
#include <vector>

namespace OpenMeshSkinned {

/// Runs \p work(t) for every t in [0, threads) at once, work(0) on the calling thread; returns when all
/// have returned. With threads <= 1, only work(0) runs.
template <typename Work>
void run_on_threads(int threads, Work&& work) {
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back([&work, t] { work(t); });
  work(0);
  for (auto& th : pool) th.join();
}

}  // namespace OpenMeshSkinned
