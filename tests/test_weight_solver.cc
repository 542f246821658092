#include <OpenMeshSkinned/Solver/WeightSolver.hh>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace OpenMeshSkinned;
using Mat = WeightSolver::Matrix;
using Vec = WeightSolver::Vector;

namespace {

void expect_feasible(const Vec& a, int cap) {
  EXPECT_NEAR(a.sum(), 1.0, 1e-9);
  EXPECT_GE(a.minCoeff(), 0.0);
  EXPECT_LE((a.array() > 0.0).count(), cap);
}

// A random PSD weight Gram matrix like the collapse solver builds: sum of V^T Q V over poses.
Mat random_gram(std::mt19937& rng, int m, int poses) {
  std::normal_distribution<double> n(0.0, 1.0);
  Mat H = Mat::Zero(m, m);
  for (int p = 0; p < poses; ++p) {
    Eigen::Matrix<double, 4, Eigen::Dynamic> V(4, m);
    for (int k = 0; k < m; ++k) V.col(k) << n(rng), n(rng), n(rng), 1.0;
    Eigen::Vector4d plane(n(rng), n(rng), n(rng), n(rng));
    H += V.transpose() * plane * plane.transpose() * V;
  }
  return H;
}

double brute_force_simplex3(const Mat& H) {
  double best = HUGE_VAL;
  const int N = 600;
  for (int i = 0; i <= N; ++i)
    for (int j = 0; i + j <= N; ++j) {
      Vec a(3);
      a << double(i) / N, double(j) / N, double(N - i - j) / N;
      best = std::min(best, a.dot(H * a));
    }
  return best;
}

}  // namespace

TEST(WeightSolver, InteriorOptimumIsTheClosedForm) {
  // min sum h_k a_k^2 with sum a = 1: a_k proportional to 1 / h_k.
  Mat H = Mat::Zero(3, 3);
  H.diagonal() << 1.0, 2.0, 4.0;
  Vec start = Vec::Constant(3, 1.0 / 3.0), a;
  WeightSolver ws;
  ws.solve(H, start, a);
  const Eigen::Vector3d expect = Eigen::Vector3d(1.0, 0.5, 0.25) / 1.75;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], expect[k], 1e-6);
  EXPECT_EQ(ws.stats().ceres_calls, 0u);
}

TEST(WeightSolver, BoundsHoldWhereTheClosedFormGoesNegative) {
  // min (sum a_k c_k)^2, c = (1, 2, 3): without a >= 0, a = (2, -1, 0) reaches 0; with it, a = (1, 0, 0).
  Eigen::Vector3d c(1, 2, 3);
  Mat H = c * c.transpose();
  Vec start = Vec::Constant(3, 1.0 / 3.0), a;
  WeightSolver ws;
  const double e = ws.solve(H, start, a);
  expect_feasible(a, 3);
  EXPECT_NEAR(a[0], 1.0, 1e-6);
  EXPECT_NEAR(e, 1.0, 1e-5);
}

TEST(WeightSolver, MatchesBruteForceOnTheSimplex) {
  std::mt19937 rng(7);
  WeightSolver ws;
  for (int t = 0; t < 30; ++t) {
    const Mat H = random_gram(rng, 3, 1 + t % 4);
    Vec start = Vec::Constant(3, 1.0 / 3.0), a;
    const double e = ws.solve(H, start, a);
    expect_feasible(a, 3);
    EXPECT_LE(e, brute_force_simplex3(H) + 1e-6 * (1.0 + H.norm())) << "case " << t;
  }
}

TEST(WeightSolver, CeresAndTheCertifiedClosedFormAgree) {
  std::mt19937 rng(11);
  WeightSolver closed, ceres;
  ceres.set_force_ceres(true);
  for (int t = 0; t < 40; ++t) {
    const int m = 2 + t % 6;
    const Mat H = random_gram(rng, m, 1 + t % 3);
    Vec start = Vec::Constant(m, 1.0 / m), a, b;
    const double ea = closed.solve(H, start, a);
    const double eb = ceres.solve(H, start, b);
    expect_feasible(a, m);
    expect_feasible(b, m);
    EXPECT_NEAR(ea, eb, 1e-6 * (1.0 + std::abs(ea))) << "case " << t;
  }
  EXPECT_EQ(ceres.stats().ceres_calls, ceres.stats().solves);
}

TEST(WeightSolver, CapStrategiesRespectTheCapAndGreedyIsNoWorseOnAverage) {
  std::mt19937 rng(3);
  WeightSolver ws;
  double sum_top = 0.0, sum_greedy = 0.0;
  for (int t = 0; t < 60; ++t) {
    const int m = 6 + t % 6;
    const Mat H = random_gram(rng, m, 3 + t % 5) + 1e-3 * Mat::Identity(m, m);
    Vec start = Vec::Constant(m, 1.0 / m), a, b;
    for (int cap : {1, 2, 4}) {
      const double et = ws.solve_capped(H, start, cap, CapStrategy::TopN, a);
      const double eg = ws.solve_capped(H, start, cap, CapStrategy::Greedy, b);
      expect_feasible(a, cap);
      expect_feasible(b, cap);
      sum_top += et;
      sum_greedy += eg;
    }
  }
  EXPECT_LE(sum_greedy, sum_top);
}

TEST(WeightSolver, SingleJointIsTrivial) {
  Mat H = Mat::Constant(1, 1, 5.0);
  Vec start = Vec::Constant(1, 1.0), a;
  WeightSolver ws;
  EXPECT_NEAR(ws.solve(H, start, a), 5.0, 1e-9);
  EXPECT_EQ(a[0], 1.0);
}

TEST(WeightSolver, HugeNearlySingularGramMatricesStillGiveWeightsSummingToOne) {
  // Characters in centimetres with scaled armatures give weight Gram matrices of 1e9 and more with a
  // rank below the joint count: the closed form's system is then nearly singular and may return a point
  // far off sum(a) = 1, which must not be taken as the answer.
  std::mt19937 rng(5);
  WeightSolver ws;
  for (int t = 0; t < 200; ++t) {
    const int m = 3 + t % 4;
    const Mat H = std::pow(10.0, 6 + t % 6) * random_gram(rng, m, 1 + t % 2);
    Vec start = Vec::Constant(m, 0.0), a;
    start[t % m] = 0.5;
    start[(t + 1) % m] += 0.5;
    ws.solve(H, start, a);
    ASSERT_NEAR(a.sum(), 1.0, 1e-9) << "trial " << t;
    expect_feasible(a, m);
  }
}

TEST(WeightSolver, ANonFiniteProblemIsRefusedAtOnceWithTheStartsWeights) {
  // A NaN or overflowed Gram matrix (a corrupt key, huge coordinates) has no answer: the solve must end at
  // once with an infinite error (the collapse is refused) and still leave a valid skin behind, capped.
  std::mt19937 rng(11);
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (CapStrategy strategy : {CapStrategy::Greedy, CapStrategy::TopN}) {
      WeightSolver ws;
      const int m = 8;
      Mat H = random_gram(rng, m, 3);
      H(2, 5) = H(5, 2) = bad;
      Vec start(m), a;
      start << 0.3, 0.2, 0.15, 0.1, 0.1, 0.05, 0.05, 0.05;
      EXPECT_TRUE(std::isinf(ws.solve(H, start, a)));
      EXPECT_TRUE(std::isinf(ws.solve_capped(H, start, 4, strategy, a)));
      expect_feasible(a, 4);
      EXPECT_GT(a[0], a[3]);  // the start's heaviest four, in their proportions
      EXPECT_NEAR(a[0] / a[1], 1.5, 1e-12);
      EXPECT_EQ(ws.stats().ceres_calls, 0u);
      EXPECT_GE(ws.stats().non_finite, 2u);
    }
  }
}
