// The per-edge answer cache of the collapse solver (Solver/EdgeCache.hh).
#include <OpenMeshSkinned/Solver/EdgeCache.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

TEST(EdgeCache, AnAnswerHoldsUntilAnEndpointChanges) {
  EdgeCache cache;
  cache.reset(4, 5);
  EXPECT_EQ(cache.find(2, 1, 3), nullptr);
  cache.store(2, 1, 3).error = 7.0;
  ASSERT_NE(cache.find(2, 1, 3), nullptr);
  EXPECT_EQ(cache.find(2, 1, 3)->error, 7.0);
  cache.touch(4);  // another vertex: still valid
  EXPECT_NE(cache.find(2, 1, 3), nullptr);
  cache.touch(3);
  EXPECT_EQ(cache.find(2, 1, 3), nullptr);
}

TEST(EdgeCache, AnEdgeSlotReusedForOtherEndpointsIsNotAHit) {
  // After garbage collection or a collapse, an edge index may join other vertices.
  EdgeCache cache;
  cache.reset(1, 4);
  cache.store(0, 0, 1);
  EXPECT_EQ(cache.find(0, 0, 2), nullptr);
  EXPECT_NE(cache.find(0, 0, 1), nullptr);
  cache.invalidate();
  EXPECT_EQ(cache.find(0, 0, 1), nullptr);
}
