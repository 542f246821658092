#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Eval/TriangleBvh.hh>
#include <OpenMeshSkinned/Mesh/ClosestPoint.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <climits>
#include <cmath>
#include <random>

using namespace OpenMeshSkinned;

namespace {

// What trying every triangle gives: the least (squared distance, index).
double brute_force(const TriangleSoup& s, const Eigen::Vector3d& q, int& triangle) {
  double best = HUGE_VAL;
  triangle = -1;
  for (size_t i = 0; i < s.triangles.size(); ++i) {
    const auto& t = s.triangles[i];
    const Eigen::Vector3d c[3] = {s.points[t[0]], s.points[t[1]], s.points[t[2]]};
    Eigen::Vector3d bary;
    const double d = closest_barycentric(c, q, bary);
    if (d < best) {
      best = d;
      triangle = int(i);
    }
  }
  return best;
}

// The bending cylinder at a time \p t of its clip, with a few degenerate and repeated triangles added.
TriangleSoup cylinder(double t) {
  const SkinnedMesh mesh = make_bending_cylinder(12, 24);
  TriangleSoup s = posed_soup(mesh, sample_pose(skeleton(mesh), clips(mesh).at(0), t * clips(mesh)[0].duration));
  const int n = int(s.triangles.size());
  s.triangles.push_back({0, 0, 1});                                                  // a segment
  s.triangles.push_back({2, 2, 2});                                                  // a point
  s.triangles.push_back(s.triangles[n / 2]);                                         // the same triangle twice
  s.triangles.push_back({s.triangles[7][1], s.triangles[7][2], s.triangles[7][0]});  // rotated
  return s;
}

// Points on the soup's triangles and on their edges, as the measures draw them (area samples, a LOD
// vertex's nearest point on the original): where ties between triangles sharing an edge are decided by the
// last bits of closest_barycentric().
std::vector<Eigen::Vector3d> on_surface(const TriangleSoup& s, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> q;
  for (int i = 0; i < n; ++i) {
    const auto& t = s.triangles[rng() % (s.triangles.size() - 4)];
    double r1 = u(rng), r2 = i % 2 ? 1.0 - r1 : u(rng);  // odd: on the edge from corner 1 to corner 2
    if (r1 + r2 > 1.0) {
      r1 = 1.0 - r1;
      r2 = 1.0 - r2;
    }
    q.push_back(s.points[t[0]] + r1 * (s.points[t[1]] - s.points[t[0]]) + r2 * (s.points[t[2]] - s.points[t[0]]));
  }
  return q;
}

// Every query answered as trying every triangle answers it: the same distance and triangle, bit for bit.
void expect_brute_force_answers(const TriangleBvh& bvh, const TriangleSoup& s, const std::vector<Eigen::Vector3d>& qs) {
  for (const Eigen::Vector3d& q : qs) {
    int expected = -1, found = -1;
    const double d = brute_force(s, q, expected);
    EXPECT_EQ(bvh.nearest(q, found), d);
    EXPECT_EQ(found, expected);
  }
}

std::vector<Eigen::Vector3d> queries(const TriangleSoup& s, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> q;
  for (int i = 0; i < n; ++i) {
    // Near the surface, far from it, and on it.
    const Eigen::Vector3d& p = s.points[rng() % s.points.size()];
    const double reach = i % 3 == 0 ? 0.01 : (i % 3 == 1 ? 0.3 : 3.0);
    q.push_back(i % 10 == 9 ? p : Eigen::Vector3d(p + reach * Eigen::Vector3d(u(rng), u(rng), u(rng))));
  }
  return q;
}

}  // namespace

TEST(TriangleBvh, FindsWhatTryingEveryTriangleFindsBitForBit) {
  const TriangleSoup s = cylinder(0.4);
  const TriangleBvh bvh(s);
  EXPECT_EQ(bvh.size(), s.triangles.size());
  expect_brute_force_answers(bvh, s, queries(s, 600, 1));
}

TEST(TriangleBvh, OnTheSurfaceAndFarFromTheOriginItStillFindsWhatTryingEveryTriangleFinds) {
  for (double offset : {0.0, 1e6}) {
    TriangleSoup s = cylinder(0.7);
    for (auto& p : s.points) p += Eigen::Vector3d(offset, -offset, 0.5 * offset);
    const TriangleBvh bvh(s);
    int hint_source = 0;
    for (const Eigen::Vector3d& q : on_surface(s, 2000, 11)) {
      int expected = -1, found = -1, hinted = -1;
      const double d = brute_force(s, q, expected);
      EXPECT_EQ(bvh.nearest(q, found), d) << "offset " << offset;
      EXPECT_EQ(found, expected) << "offset " << offset;
      EXPECT_EQ(bvh.nearest(q, hinted, (hint_source += 37) % int(s.triangles.size())), d);
      EXPECT_EQ(hinted, expected);
    }
  }
}

// A sheet folded by a hair along its middle, cut into needles and slivers of every thinness: where a
// triangle's plane says little (a near-flat fold, an in-plane neighbour) or its normal cannot be trusted
// (a sliver), the search must still try it.
TEST(TriangleBvh, SliversAndNearlyFlatFoldsAreStillFound) {
  for (double offset : {0.0, 1e5}) {
    TriangleSoup s;
    const int columns = 40;
    for (int i = 0; i <= columns; ++i) {
      const double x = double(i) / columns;
      const double crease = 1e-7 * std::abs(x - 0.5);                   // a fold of 1e-7 radians along x = 0.5
      const double thin = std::pow(10.0, -1.0 - 12.0 * (i % 7) / 6.0);  // needles 0.1 to 1e-13 wide
      for (double y : {0.0, thin, 1.0})
        s.points.push_back(Eigen::Vector3d(x + offset, y - offset, crease + 0.5 * offset));
    }
    for (int i = 0; i < columns; ++i) {
      const int a = 3 * i, b = 3 * (i + 1);
      s.triangles.push_back({a, b, a + 1});
      s.triangles.push_back({b, b + 1, a + 1});
      s.triangles.push_back({a + 1, b + 1, a + 2});
      s.triangles.push_back({b + 1, b + 2, a + 2});
    }
    const TriangleBvh bvh(s);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Eigen::Vector3d> qs = on_surface(s, 1000, 3);
    for (int i = 0; i < 1000; ++i)
      qs.push_back(Eigen::Vector3d(u(rng) + offset, 1.2 * u(rng) - 0.1 - offset,
                                   std::pow(10.0, -9.0 * u(rng)) * (i % 2 ? 1.0 : -1.0) + 0.5 * offset));
    expect_brute_force_answers(bvh, s, qs);
    for (size_t i = 0; i < qs.size(); ++i) {
      int expected = -1, hinted = -1;
      const double d = brute_force(s, qs[i], expected);
      EXPECT_EQ(bvh.nearest(qs[i], hinted, int(i % s.triangles.size())), d) << "offset " << offset;
      EXPECT_EQ(hinted, expected) << "offset " << offset;
    }
  }
}

// A sliver turned off the axes: its corners' cross product is mostly rounding, so its plane says nothing.
// Under each one lies a wider triangle a hair away, searched first (the hint), which a wrong plane would
// keep in place of the sliver the query is on.
TEST(TriangleBvh, ATurnedSliverIsTriedThoughItsCrossProductIsRounding) {
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  const Eigen::Vector3d u = turn.col(0), v = turn.col(1), n = turn.col(2);
  TriangleSoup s;
  std::vector<int> under;  // the wider triangle beneath each sliver
  for (int k = 0; k < 10; ++k) {
    const double width = std::pow(10.0, -6.0 - k);  // 1e-6 to 1e-15 across a length of 1
    const Eigen::Vector3d c = 2.0 * k * v;
    const int base = int(s.points.size());
    for (const Eigen::Vector3d& p : {c, Eigen::Vector3d(c + u), Eigen::Vector3d(c + 0.5 * u + width * v)})
      s.points.push_back(p);
    for (const Eigen::Vector3d& p : {c, Eigen::Vector3d(c + u), Eigen::Vector3d(c + 0.5 * u + 0.3 * v)})
      s.points.push_back(p - 1e-3 * n);
    s.triangles.push_back({base, base + 1, base + 2});
    under.push_back(int(s.triangles.size()));
    s.triangles.push_back({base + 3, base + 4, base + 5});
  }
  const TriangleBvh bvh(s);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int k = 0; k < 10; ++k)
    for (int i = 0; i < 50; ++i) {
      const auto& t = s.triangles[2 * k];
      const double a = uniform(rng), b = (1.0 - a) * uniform(rng);
      const Eigen::Vector3d q = a * s.points[t[0]] + b * s.points[t[1]] + (1.0 - a - b) * s.points[t[2]];
      int expected = -1, found = -1;
      const double d = brute_force(s, q, expected);
      EXPECT_EQ(bvh.nearest(q, found, under[k]), d) << "sliver " << k;
      EXPECT_EQ(found, expected) << "sliver " << k;
    }
}

TEST(TriangleBvh, AHintChangesNothingButTheSearch) {
  const TriangleSoup s = cylinder(0.9);
  const TriangleBvh bvh(s);
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> any(-3, int(s.triangles.size()) + 3);  // out of range too
  for (const Eigen::Vector3d& q : queries(s, 400, 2)) {
    int plain = -1, hinted = -1;
    const double d = bvh.nearest(q, plain);
    EXPECT_EQ(bvh.nearest(q, hinted, any(rng)), d);
    EXPECT_EQ(hinted, plain);
    EXPECT_EQ(bvh.nearest(q, hinted, plain), d);
    EXPECT_EQ(hinted, plain);
  }
}

// One triangle's distance is an upper bound on the search's, equal to it for the triangle found, computed
// the same way (what lets the held-out measure skip a search when the bound cannot raise its maximum).
TEST(TriangleBvh, OneTrianglesDistanceBoundsTheNearest) {
  const TriangleSoup s = cylinder(0.6);
  const TriangleBvh bvh(s);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> any(0, int(s.triangles.size()) - 1);
  for (const Eigen::Vector3d& q : queries(s, 300, 3)) {
    int found = -1;
    const double d = bvh.nearest(q, found);
    EXPECT_EQ(bvh.distance2_to(q, found), d);
    EXPECT_GE(bvh.distance2_to(q, any(rng)), d);
  }
  const Eigen::Vector3d q = s.points[0];
  EXPECT_EQ(bvh.distance2_to(q, -1), HUGE_VAL);
  EXPECT_EQ(bvh.distance2_to(q, int(s.triangles.size())), HUGE_VAL);
  EXPECT_EQ(bvh.distance2_to(Eigen::Vector3d(NAN, 0.0, 0.0), 0), HUGE_VAL);
}

TEST(TriangleBvh, TiesGoToTheLowerIndex) {
  const TriangleSoup s = cylinder(0);
  const TriangleBvh bvh(s);
  const int n = int(s.triangles.size()) - 4;
  const auto& t = s.triangles[n / 2];  // repeated at n + 2
  const Eigen::Vector3d centre = (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0;
  int found = -1;
  EXPECT_EQ(bvh.nearest(centre, found, n + 2), 0.0);
  EXPECT_EQ(found, n / 2);
}

TEST(TriangleBvh, ARefittedHierarchyAnswersAsAFreshOne) {
  const TriangleSoup rest = cylinder(0), bent = cylinder(0.9);
  ASSERT_GT((rest.points.back() - bent.points.back()).norm(), 0.1);  // the pose moves it
  TriangleBvh moved(rest);
  moved.refit(bent.points);
  const TriangleBvh fresh(bent);
  const std::vector<Eigen::Vector3d> qs = queries(bent, 400, 3);
  expect_brute_force_answers(moved, bent, qs);
  expect_brute_force_answers(fresh, bent, qs);
  // Too few points: refused before anything moves.
  EXPECT_THROW(moved.refit(std::vector<Eigen::Vector3d>(3)), std::out_of_range);
  expect_brute_force_answers(moved, bent, queries(bent, 50, 4));
}

TEST(TriangleBvh, BadCornersAreRefusedOrSkipped) {
  TriangleSoup s = cylinder(0);
  TriangleSoup bad = s;
  bad.triangles.push_back({0, 1, int(s.points.size())});
  EXPECT_THROW(TriangleBvh{bad}, std::out_of_range);
  // A corner that is not a number: its triangles are never the nearest; the others are found as before.
  s.points[3] = Eigen::Vector3d(NAN, 0.0, 0.0);
  const TriangleBvh bvh(s);
  expect_brute_force_answers(bvh, s, queries(s, 200, 6));
}

TEST(TriangleBvh, NothingToFind) {
  int t = 7;
  EXPECT_EQ(TriangleBvh().nearest(Eigen::Vector3d::Zero(), t), HUGE_VAL);
  EXPECT_EQ(t, -1);
  const TriangleSoup s = cylinder(0);
  const TriangleBvh bvh(s);
  EXPECT_EQ(bvh.nearest(Eigen::Vector3d(NAN, 0.0, 0.0), t), HUGE_VAL);
  EXPECT_EQ(t, -1);
  TriangleSoup one;
  one.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  EXPECT_DOUBLE_EQ(TriangleBvh(one).nearest(Eigen::Vector3d(0.25, 0.25, 2.0), t), 4.0);
  EXPECT_EQ(t, 0);
}

TEST(TriangleBvh, RankKeepsNeighboursTogether) {
  // A 40 x 40 grid whose triangles come in a shuffled order: the order the measures draw samples in.
  TriangleSoup s;
  const int n = 40;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) s.points.emplace_back(x, y, 0.0);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x;
      s.triangles.push_back({a, a + 1, a + n + 2});
      s.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  std::shuffle(s.triangles.begin(), s.triangles.end(), std::mt19937(3));
  const TriangleBvh bvh(s);
  const int m = int(s.triangles.size());
  std::vector<int> by_rank(m, -1);
  for (int t = 0; t < m; ++t) {
    const int r = bvh.rank(t);
    ASSERT_GE(r, 0);
    ASSERT_LT(r, m);
    EXPECT_EQ(by_rank[r], -1) << "rank " << r << " given twice";
    by_rank[r] = t;
  }
  EXPECT_EQ(bvh.rank(-1), -1);
  EXPECT_EQ(bvh.rank(m), -1);
  auto centre = [&](int t) {
    return (s.points[s.triangles[t][0]] + s.points[s.triangles[t][1]] + s.points[s.triangles[t][2]]) / 3.0;
  };
  double by_index = 0.0, in_rank_order = 0.0;
  for (int k = 1; k < m; ++k) {
    by_index += (centre(k) - centre(k - 1)).norm();
    in_rank_order += (centre(by_rank[k]) - centre(by_rank[k - 1])).norm();
  }
  // Shuffled, consecutive triangles are about a third of the grid apart; in rank order, about one cell.
  EXPECT_LT(in_rank_order / (m - 1), 2.0);
  EXPECT_GT(by_index / (m - 1), 10.0);
}

TEST(MeasuredSurface, PosedAgainItMeasuresAsOneBuiltInThatPose) {
  const TriangleSoup rest = cylinder(0), bent = cylinder(0.9), other = cylinder(0.4);
  MeasuredSurface reposed(rest, 2000, 5);
  reposed.repose(bent);
  const MeasuredSurface fresh(bent, 2000, 5), against(other, 2000, 6);
  const SurfaceDistance a = surface_distance(reposed, against), b = surface_distance(fresh, against);
  EXPECT_GT(a.rms, 0.0);
  EXPECT_EQ(a.rms, b.rms);
  EXPECT_EQ(a.hausdorff, b.hausdorff);
  EXPECT_EQ(a.samples, b.samples);
  TriangleSoup fewer = bent, other_triangles = bent;
  fewer.triangles.pop_back();
  EXPECT_THROW(reposed.repose(fewer), std::invalid_argument);
  std::swap(other_triangles.triangles[0][0], other_triangles.triangles[0][1]);
  EXPECT_THROW(reposed.repose(other_triangles), std::invalid_argument);
}

TEST(MeasuredSurface, RanksItsTrianglesAsItsHierarchyDoes) {
  const TriangleSoup s = cylinder(0.3);
  const MeasuredSurface surface(s, 0, 1);
  const TriangleBvh bvh(s);
  for (int t = -1; t <= int(s.triangles.size()); ++t) EXPECT_EQ(surface.rank(t), bvh.rank(t)) << t;
}
