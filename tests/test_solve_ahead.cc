// SolveAhead: a worker fills and solves submitted edges into the edge cache; its answers are the serial
// solve's, an edge whose job it has not started goes back to the mesh thread, and a vertex released by the
// mesh thread is read by no job afterwards.
#include <OpenMeshSkinned/Solver/SolveAhead.hh>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>

using namespace OpenMeshSkinned;

namespace {

// A random edge: two or three joints, three poses of random rigid motions, random planes per pose.
EdgeProblem random_problem(std::mt19937& rng, Influences* skin_a = nullptr, Influences* skin_b = nullptr) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EdgeProblem p;
  Influences wa, wb;
  wa.push(0, 0.6);
  wa.push(1, 0.4);
  wb.push(1, 0.7);
  wb.push(u(rng) > 0.0 ? 2 : 0, 0.3);
  wa.sort();
  wb.sort();
  p.set_skins(wa, wb);
  if (skin_a) *skin_a = wa;
  if (skin_b) *skin_b = wb;
  p.resize(3);
  for (int j = 0; j < 3; ++j) {
    Pose pose = Pose::identity(3);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d R =
          Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1.0).normalized()).toRotationMatrix();
      pose.joint[k].leftCols<3>() = R;
      pose.joint[k].col(3) = 0.2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    }
    p.set_pose(j, pose);
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
      p.quadric[j] += PoseQuadric::plane(n, 0.3 * u(rng), 0.5 + 0.5 * u(rng));
    }
  }
  p.pa = Eigen::Vector3d(u(rng), u(rng), u(rng));
  p.pb = p.pa + 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return p;
}

}  // namespace

TEST(SolveAhead, TheWorkersAnswersAreTheSerialSolvesAndLandInTheCache) {
  constexpr int kEdges = int(SolveAhead::kRing);  // as many as can wait at once
  std::mt19937 rng(5);
  std::vector<EdgeProblem> problems;
  for (int e = 0; e < kEdges; ++e) problems.push_back(random_problem(rng));
  EdgeCache cache;
  cache.reset(kEdges, 2 * kEdges);
  const SolveSettings settings;
  WeightSolver serial;
  // Edge e joins vertices 2e and 2e + 1; the worker fills its problem, as the decimation's loader does.
  SolveAhead ahead(cache, kEdges, settings, serial, [&](int a, int b, EdgeProblem& p) {
    ASSERT_EQ(b, a + 1);
    p = problems[size_t(a / 2)];
  });
  for (int e = 0; e < kEdges; ++e) ASSERT_TRUE(ahead.submit(e, 2 * e, 2 * e + 1, 0, 0));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (ahead.solved() < kEdges && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(ahead.solved(), size_t(kEdges));
  for (int e = 0; e < kEdges; ++e) {
    ahead.settle(e);
    CollapseResult got;
    ASSERT_TRUE(cache.find(e, 2 * e, 2 * e + 1, got)) << "edge " << e;
    CollapseResult want;
    solve_collapse(problems[e], settings, serial, want);
    EXPECT_EQ(got.position, want.position) << "edge " << e;
    EXPECT_EQ(got.error, want.error);
    EXPECT_EQ(got.weights, want.weights);
    EXPECT_EQ(got.valid, want.valid);
  }
  // Answers are tied to the stamps they were solved at: a vertex that changed since has none.
  cache.touch(0);
  EXPECT_FALSE(cache.has(0, 0, 1));
  ahead.stop();
  EXPECT_GT(ahead.worker_stats().solves, 0u);
}

TEST(SolveAhead, AJobTheWorkerHasNotStartedGoesBackToTheMeshThread) {
  std::mt19937 rng(6);
  EdgeCache cache;
  cache.reset(4, 8);
  WeightSolver like;
  SolveAhead ahead(cache, 4, SolveSettings{}, like, [&](int, int, EdgeProblem& p) { p = random_problem(rng); });
  ahead.stop();  // nothing will be started
  for (int e = 0; e < 4; ++e) ASSERT_TRUE(ahead.submit(e, 2 * e, 2 * e + 1, 0, 0));
  for (int e = 0; e < 4; ++e) {
    ahead.settle(e);  // cancels: the entry is the mesh thread's, and empty
    EXPECT_FALSE(cache.has(e, 2 * e, 2 * e + 1));
    CollapseResult mine;
    mine.error = 7.0;
    cache.store(e, 2 * e, 2 * e + 1, mine);  // what the mesh thread then solves stays
  }
  for (int e = 0; e < 4; ++e) {
    CollapseResult got;
    ASSERT_TRUE(cache.find(e, 2 * e, 2 * e + 1, got));
    EXPECT_EQ(got.error, 7.0);
  }
  EXPECT_EQ(ahead.solved(), 0u);
}

TEST(SolveAhead, AReleasedVertexIsReadByNoJobAfterwards) {
  std::mt19937 rng(7);
  const EdgeProblem problem = random_problem(rng);
  EdgeCache cache;
  cache.reset(3, 6);
  WeightSolver like;
  std::atomic<int> reading{-1};  // the edge whose problem the worker is filling
  std::atomic<bool> hold{true};  // keeps the worker in the first job's loader
  std::atomic<int> loaded_after{0};
  std::atomic<bool> released{false};
  SolveAhead ahead(cache, 3, SolveSettings{}, like, [&](int a, int, EdgeProblem& p) {
    reading = a / 2;
    while (hold) std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (released) ++loaded_after;
    p = problem;
  });
  // Edge 0 (vertices 0, 1) is being filled; edge 1 (vertices 1, 2) waits behind it; edge 2 (vertices 4, 5)
  // does not touch vertex 1.
  ASSERT_TRUE(ahead.submit(0, 0, 1, 0, 0));
  while (reading != 0) std::this_thread::yield();
  ASSERT_TRUE(ahead.submit(1, 1, 2, 0, 0));
  ASSERT_TRUE(ahead.submit(2, 4, 5, 0, 0));
  std::thread let_go([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    hold = false;
  });
  ahead.release_vertex(1);  // waits for edge 0's job, drops edge 1's
  released = true;
  let_go.join();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (ahead.solved() < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ahead.stop();
  EXPECT_EQ(loaded_after, 1);  // edge 2 alone was filled after the release
  EXPECT_EQ(ahead.solved(), 2u);
  for (int e : {0, 1, 2}) ahead.settle(e);
  EXPECT_TRUE(cache.has(0, 0, 1));
  EXPECT_FALSE(cache.has(1, 1, 2));  // the mesh thread's to solve
  EXPECT_TRUE(cache.has(2, 4, 5));
}
