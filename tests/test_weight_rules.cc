// The weight-update rules of the baselines and the cap they respect (Solver/WeightRules.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Solver/WeightRules.hh>

using namespace OpenMeshSkinned;

namespace {
Influences skin(std::initializer_list<JointWeight> l) {
  Influences inf;
  for (const auto& jw : l) inf.push(jw.joint, jw.weight);
  inf.sort();
  return inf;
}
}  // namespace

TEST(WeightRules, PowerSkinningOnTwoEquidistantVerticesAverages) {
  const Influences a = skin({{0, 1.0}}), b = skin({{1, 0.6}, {2, 0.4}});
  const Influences m = merge_weights(WeightRule::PowerSkinning, Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0, 0, 0), a,
                                     Eigen::Vector3d(1, 0, 0), b, 4);
  EXPECT_NEAR(m.weight_of(0), 0.5, 1e-12);
  EXPECT_NEAR(m.weight_of(1), 0.3, 1e-12);
  EXPECT_NEAR(m.weight_of(2), 0.2, 1e-12);
}

TEST(WeightRules, DistanceInterpolationFollowsThePlacement) {
  const Influences a = skin({{0, 1.0}}), b = skin({{1, 1.0}});
  const Eigen::Vector3d p0(0, 0, 0), p1(4, 0, 0);
  // At a quarter of the way from v0: t = 1/4, three quarters of v0's skin.
  const Influences m = merge_weights(WeightRule::DistanceInterpolation, Eigen::Vector3d(1, 0, 0), p0, a, p1, b, 4);
  EXPECT_NEAR(m.weight_of(0), 0.75, 1e-12);
  // For an edge, Savoye-Meyer's power skinning is the same blend.
  const Influences q = merge_weights(WeightRule::PowerSkinning, Eigen::Vector3d(1, 0, 0), p0, a, p1, b, 4);
  EXPECT_TRUE(m == q);
  // At an endpoint, that endpoint's skin.
  EXPECT_TRUE(merge_weights(WeightRule::DistanceInterpolation, p1, p0, a, p1, b, 4) == b);
}

TEST(WeightRules, NearestEndpointCopiesAndEveryRuleRespectsTheCap) {
  const Influences a = skin({{0, 0.5}, {1, 0.3}, {2, 0.2}}), b = skin({{3, 0.7}, {4, 0.3}});
  const Eigen::Vector3d p0(0, 0, 0), p1(1, 0, 0);
  EXPECT_TRUE(merge_weights(WeightRule::NearestEndpoint, Eigen::Vector3d(0.2, 0, 0), p0, a, p1, b, 4) == a);
  for (WeightRule r : {WeightRule::NearestEndpoint, WeightRule::DistanceInterpolation, WeightRule::PowerSkinning}) {
    const Influences m = merge_weights(r, Eigen::Vector3d(0.5, 0.1, 0), p0, a, p1, b, 2);
    EXPECT_LE(m.size(), 2);
    EXPECT_NEAR(m.sum(), 1.0, 1e-12);
    for (const auto& jw : m) EXPECT_GT(jw.weight, 0.0);
  }
}
