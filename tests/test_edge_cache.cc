// The per-edge answer cache of the collapse solver (Solver/EdgeCache.hh).
#include <OpenMeshSkinned/Solver/EdgeCache.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

TEST(EdgeCache, AnAnswerHoldsUntilAnEndpointChanges) {
  EdgeCache cache;
  cache.reset(4, 5);
  CollapseResult r;
  EXPECT_FALSE(cache.find(2, 1, 3, r));
  r.error = 7.0;
  cache.store(2, 1, 3, r);
  CollapseResult got;
  ASSERT_TRUE(cache.find(2, 1, 3, got));
  EXPECT_EQ(got.error, 7.0);
  cache.touch(4);  // another vertex: still valid
  EXPECT_TRUE(cache.has(2, 1, 3));
  cache.touch(3);
  EXPECT_FALSE(cache.has(2, 1, 3));
}

TEST(EdgeCache, AnAnswerReadBackIsTheAnswerStored) {
  // Stored compactly (16-bit joints, no padding), read back exactly: position, error, area, validity and
  // every influence, the weights to the last bit, up to the highest joint index the cache allows.
  CollapseResult r;
  r.position = Eigen::Vector3d(0.1, -2.0 / 3.0, 1e9 + 0.5);
  r.error = 1.0 / 3.0;
  r.area = 2.5e-7;
  r.valid = true;
  for (int i = 0; i < Influences::kCapacity; ++i)
    r.weights.push(i == 0 ? EdgeCache::kMaxJoints - 1 : 7 * i, (i + 1) / 36.0);
  EdgeCache cache;
  cache.reset(1, 2);
  cache.store(0, 0, 1, r);
  CollapseResult got;
  ASSERT_TRUE(cache.find(0, 0, 1, got));
  EXPECT_EQ(got.position, r.position);
  EXPECT_EQ(got.error, r.error);
  EXPECT_EQ(got.area, r.area);
  EXPECT_EQ(got.valid, r.valid);
  EXPECT_EQ(got.weights, r.weights);
  EXPECT_EQ(got.weights[0].joint, EdgeCache::kMaxJoints - 1);
}

TEST(EdgeCache, AnEdgeSlotReusedForOtherEndpointsIsNotAHit) {
  // After garbage collection or a collapse, an edge index may join other vertices.
  EdgeCache cache;
  cache.reset(1, 4);
  cache.store(0, 0, 1, CollapseResult{});
  EXPECT_FALSE(cache.has(0, 0, 2));
  EXPECT_TRUE(cache.has(0, 0, 1));
  cache.invalidate();
  EXPECT_FALSE(cache.has(0, 0, 1));
}

TEST(EdgeCache, AnAnswerWithMoreInfluencesThanASlotHoldsIsSolvedAgain) {
  // Slots sized for the cap: an answer beyond it is not kept (never cut short), one within it is.
  EdgeCache cache;
  cache.reset(2, 4, 4);
  EXPECT_EQ(cache.capacity(), 4);
  CollapseResult wide, narrow, got;
  for (int i = 0; i < 5; ++i) wide.weights.push(i, 0.2);
  for (int i = 0; i < 4; ++i) narrow.weights.push(i, 0.25);
  cache.store(0, 0, 1, wide);
  EXPECT_FALSE(cache.find(0, 0, 1, got));
  cache.store(1, 2, 3, narrow);
  ASSERT_TRUE(cache.find(1, 2, 3, got));
  EXPECT_EQ(got.weights, narrow.weights);
  // Widened (the cap was raised): every answer is gone, the wide one now fits, the stamps go on.
  cache.touch(2);
  cache.set_capacity(8);
  EXPECT_FALSE(cache.has(1, 2, 3));
  cache.store(0, 0, 1, wide);
  ASSERT_TRUE(cache.find(0, 0, 1, got));
  EXPECT_EQ(got.weights, wide.weights);
  EXPECT_EQ(cache.stamp(2), 1u);
}
