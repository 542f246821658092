// Key-frame extraction by the report's genetic algorithm, judged against the exact optimum.
#include <OpenMeshSkinned/Deform/KeyframeGA.hh>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace OpenMeshSkinned;

namespace {

// Two vertices moving along straight lines between the key frames \p keys (their positions there random):
// a piecewise-linear animation that those keys, and only those, rebuild exactly.
struct PiecewiseLinear {
  std::vector<FramePoints> frames;
  std::vector<double> times;
  PiecewiseLinear(size_t n, const std::vector<size_t>& keys, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<FramePoints> at_keys;
    for (size_t k = 0; k < keys.size(); ++k)
      at_keys.push_back({Eigen::Vector3d(g(rng), g(rng), g(rng)), Eigen::Vector3d(g(rng), g(rng), g(rng))});
    for (size_t f = 0; f < n; ++f) {
      times.push_back(0.1 * f);
      size_t k = 0;
      while (k + 2 < keys.size() && keys[k + 1] <= f) ++k;
      const double s = double(f - keys[k]) / double(keys[k + 1] - keys[k]);
      frames.push_back(
          {(1 - s) * at_keys[k][0] + s * at_keys[k + 1][0], (1 - s) * at_keys[k][1] + s * at_keys[k + 1][1]});
    }
  }
};

}  // namespace

TEST(KeyframeGA, RecoversTheTrueKeysOfAPiecewiseLinearAnimation) {
  const std::vector<size_t> keys = {0, 7, 11, 26, 30, 44, 59};
  const PiecewiseLinear anim(60, keys, 3);
  const InterpolationError err(anim.frames, anim.times);
  EXPECT_NEAR(err.total(keys), 0.0, 1e-20);
  const KeyframeSelection ga = select_keyframes_ga(err, keys.size());
  EXPECT_EQ(ga.frames, keys);
  EXPECT_LT(ga.error, 1e-20);
  // Evenly spaced keys cannot: the segments are uneven.
  EXPECT_GT(select_keyframes_even(err, keys.size()).error, 1.0);
}

TEST(KeyframeGA, ComesCloseToTheOptimumOnASmoothAnimation) {
  // A vertex on a Lissajous curve: no exact answer; the dynamic programme gives the best one.
  std::vector<FramePoints> frames;
  std::vector<double> times;
  for (int f = 0; f < 80; ++f) {
    const double t = f / 79.0;
    times.push_back(t);
    frames.push_back({Eigen::Vector3d(std::sin(6 * t), std::sin(11 * t * t), 0.3 * t)});
  }
  const InterpolationError err(frames, times);
  const double best = select_keyframes_optimal(err, 10).error;
  const KeyframeSelection ga = select_keyframes_ga(err, 10);
  EXPECT_EQ(ga.frames.size(), 10u);
  EXPECT_EQ(ga.frames.front(), 0u);
  EXPECT_EQ(ga.frames.back(), 79u);
  EXPECT_LE(ga.error, 1.1 * best);
  EXPECT_LT(ga.error, select_keyframes_even(err, 10).error);
  EXPECT_GE(ga.error, best * (1 - 1e-12));
}

TEST(KeyframeGA, TheSameSeedGivesTheSameAnswerAndBadCountsAreRefused) {
  const PiecewiseLinear anim(30, {0, 9, 20, 29}, 5);
  const InterpolationError err(anim.frames, anim.times);
  KeyframeGaSettings s;
  s.seed = 42;
  EXPECT_EQ(select_keyframes_ga(err, 5, s).frames, select_keyframes_ga(err, 5, s).frames);
  EXPECT_THROW(select_keyframes_ga(err, 1), std::invalid_argument);
  EXPECT_THROW(select_keyframes_ga(err, 31), std::invalid_argument);
  EXPECT_EQ(select_keyframes_ga(err, 30).frames.size(), 30u);
  EXPECT_EQ(select_keyframes_ga(err, 2).frames, (std::vector<size_t>{0, 29}));
}
