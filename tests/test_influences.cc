// Per-vertex influences and the cap rule (Skin/Influences.hh).
#include "helpers.hh"

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(Influences, SortedByWeightAndNormalised) {
  Influences inf;
  inf.push(3, 0.2);
  inf.push(1, 0.5);
  inf.push(2, 0.3);
  inf.sort();
  EXPECT_EQ(inf[0].joint, 1);
  EXPECT_EQ(inf[2].joint, 3);
  inf.keep_heaviest(2);
  EXPECT_EQ(inf.size(), 2);
  EXPECT_NEAR(inf[0].weight, 0.625, 1e-12);
  EXPECT_NEAR(inf.sum(), 1.0, 1e-12);
}

TEST(Influences, CapacityIsFixed) {
  Influences inf;
  for (int i = 0; i < Influences::kCapacity; ++i) EXPECT_TRUE(inf.push(i, 1.0));
  EXPECT_FALSE(inf.push(99, 1.0));
  EXPECT_EQ(inf.size(), Influences::kCapacity);
}

TEST(Influences, KeepHeaviestIsTheCapRule) {
  Influences inf;
  inf.push(4, 0.1);
  inf.push(2, 0.3);
  inf.push(9, 0.3);
  inf.push(1, 0.3);
  inf.keep_heaviest(2);
  ASSERT_EQ(inf.size(), 2);
  // Ties go to the lower joint index, so the rule gives the same skin whatever the input order.
  EXPECT_EQ(inf[0].joint, 1);
  EXPECT_EQ(inf[1].joint, 2);
  EXPECT_DOUBLE_EQ(inf[0].weight, 0.5);
  EXPECT_DOUBLE_EQ(inf.sum(), 1.0);
}

TEST(Influences, WhenFullTheLightestGivesWayToAHeavierJoint) {
  Influences inf;
  for (int j = 0; j < Influences::kCapacity; ++j) ASSERT_TRUE(inf.add_keeping_heaviest(j, 0.1 + 0.01 * j));
  EXPECT_TRUE(inf.add_keeping_heaviest(3, 0.5)) << "an existing joint still sums";
  EXPECT_FALSE(inf.add_keeping_heaviest(100, 0.05)) << "lighter than all: dropped";
  EXPECT_EQ(inf.weight_of(100), 0.0);
  EXPECT_FALSE(inf.add_keeping_heaviest(200, 0.9)) << "heavier: the lightest (joint 0) gave way";
  EXPECT_EQ(inf.weight_of(0), 0.0);
  EXPECT_DOUBLE_EQ(inf.weight_of(200), 0.9);
  EXPECT_EQ(inf.size(), Influences::kCapacity);
}

TEST(InfluenceSum, BlendsSkinsBeyondTheCapacityThenKeepsTheHeaviest) {
  // Twelve joints in two skins: more than Influences holds; the sum must not lose any before the cap.
  Influences a, b;
  for (int j = 0; j < 6; ++j) a.push(j, 1.0 / 6);
  for (int j = 6; j < 12; ++j) b.push(j, j == 11 ? 0.5 : 0.1);
  InfluenceSum sum;
  sum.add(a, 0.25);
  sum.add(b, 0.75);
  const Influences out = sum.keep_heaviest(Influences::kCapacity + 5);  // capped at the capacity
  ASSERT_EQ(out.size(), Influences::kCapacity);
  EXPECT_EQ(out[0].joint, 11) << "the heaviest blended joint comes from the second skin";
  EXPECT_NEAR(out.sum(), 1.0, 1e-12);
  const Influences two = sum.keep_heaviest(2);
  ASSERT_EQ(two.size(), 2);
  EXPECT_EQ(two[0].joint, 11);
  EXPECT_NEAR(two[0].weight, 0.375 / (0.375 + 0.075), 1e-12);
  EXPECT_TRUE(sum.keep_heaviest(0).empty());
}
