// run_on_threads (Solver/Threads.hh): every share runs once, the others on threads of their own, and the
// call returns only when all have.
#include <OpenMeshSkinned/Solver/Threads.hh>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

using namespace OpenMeshSkinned;

TEST(Threads, EveryShareRunsOnceAndTheCallWaitsForAll) {
  for (int threads : {0, 1, 2, 5}) {
    std::vector<std::atomic<int>> runs(8);
    std::mutex m;
    std::set<std::thread::id> ids;
    const auto caller = std::this_thread::get_id();
    std::thread::id first;
    run_on_threads(threads, [&](int t) {
      if (t > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));  // finishes after work(0)
      ++runs[t];
      std::lock_guard<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
      if (t == 0) first = std::this_thread::get_id();
    });
    const int n = std::max(1, threads);
    for (int t = 0; t < 8; ++t) EXPECT_EQ(runs[t].load(), t < n ? 1 : 0) << threads << " threads, share " << t;
    EXPECT_EQ(ids.size(), size_t(n)) << "each share on a thread of its own";
    EXPECT_EQ(first, caller) << "share 0 on the calling thread";
  }
}
