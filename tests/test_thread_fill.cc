// fill_on_threads (Solver/ThreadFill.hh): the table holds exactly n copies of the value whatever the
// thread count, and what it held before is gone.
#include <OpenMeshSkinned/Solver/ThreadFill.hh>

#include <gtest/gtest.h>
#include <Eigen/Core>

using namespace OpenMeshSkinned;

namespace {
struct Plain {
  double a[3];
  float b;
};
}  // namespace

TEST(ThreadFill, EveryElementHoldsTheValueWhateverTheThreadCount) {
  for (int threads : {0, 1, 2, 3, 7})
    for (size_t n : {size_t(0), size_t(1), size_t(5), size_t(1000), size_t(100003)}) {
      ThreadTable<Plain> t(17, Plain{{9, 9, 9}, 9});  // stale contents and a size that must not survive
      fill_on_threads(t, n, Plain{{1, 2, 3}, 4}, threads);
      ASSERT_EQ(t.size(), n) << threads << " threads";
      for (size_t i = 0; i < n; ++i)
        ASSERT_TRUE(t[i].a[0] == 1 && t[i].a[1] == 2 && t[i].a[2] == 3 && t[i].b == 4)
            << "element " << i << " of " << n << ", " << threads << " threads";
    }
}

TEST(ThreadFill, FillsEigenVectorsAndZeroesAValueInitialisedStruct) {
  ThreadTable<Eigen::Vector3d> v;
  fill_on_threads(v, 4099, Eigen::Vector3d(1, -2, 0.5), 2);
  for (const auto& x : v) ASSERT_EQ(x, Eigen::Vector3d(1, -2, 0.5));
  ThreadTable<Plain> z;
  fill_on_threads(z, 4099, Plain{}, 2);
  for (const auto& x : z) ASSERT_TRUE(x.a[0] == 0 && x.a[1] == 0 && x.a[2] == 0 && x.b == 0);
}
