#include "helpers.hh"

#include <OpenMeshSkinned/Lod/Evaluate.hh>
#include <OpenMeshSkinned/Mesh/ClosestPoint.hh>
#include <OpenMeshSkinned/Mesh/LoopSubdivision.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <algorithm>
#include <random>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {
TriangleSoup plane(double z, int n) {
  TriangleSoup s;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) s.points.emplace_back(double(k) / n, double(i) / n, z);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const int a = i * (n + 1) + k;
      s.triangles.push_back({a, a + 1, a + n + 2});
      s.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  return s;
}
}  // namespace

TEST(SurfaceDistance, MeshToItselfIsZero) {
  const Mesh mesh = make_bending_cylinder(16, 16);
  const auto soup = posed_soup(mesh, example_poses(mesh)[1]);
  const auto d = surface_distance(soup, soup, 5000);
  EXPECT_LT(d.hausdorff, 1e-12);
  EXPECT_LT(d.rms, 1e-12);
  EXPECT_GT(d.samples, 10000u);
}

TEST(SurfaceDistance, OffsetPlaneGivesTheOffset) {
  const auto d = surface_distance(plane(0.0, 4), plane(0.25, 7), 5000);
  EXPECT_NEAR(d.rms, 0.25, 1e-12);
  EXPECT_NEAR(d.hausdorff, 0.25, 1e-12);
}

TEST(SurfaceDistance, ErrorGrowsAsTheLodShrinksOnARealCharacter) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 6);
  const Pose held_out = sample_pose(skeleton(original), clips(original)[1], 0.37);  // another clip
  double previous = -1.0;
  for (double ratio : {0.5, 0.2, 0.05}) {
    Mesh lod = original;
    omsk_test::decimate(lod, ratio);
    const double e = omsk_test::posed_rms(original, lod, held_out);
    EXPECT_GT(e, previous) << "ratio " << ratio;
    previous = e;
  }
}

TEST(SurfaceDistance, APreparedSurfaceMeasuresAgainstManyAsAFreshOneWould) {
  const Mesh mesh = make_bending_cylinder(16, 16);
  const auto original = posed_soup(mesh, example_poses(mesh)[1]);
  const MeasuredSurface prepared(original, 3000, 1);
  for (double z : {0.01, 0.05, 0.2}) {
    TriangleSoup other = original;
    for (auto& p : other.points) p.z() += z;
    const auto reused = surface_distance(prepared, MeasuredSurface(other, 3000, 7));
    const auto fresh = surface_distance(MeasuredSurface(original, 3000, 1), MeasuredSurface(other, 3000, 7));
    EXPECT_EQ(reused.rms, fresh.rms);
    EXPECT_EQ(reused.hausdorff, fresh.hausdorff);
    EXPECT_GT(reused.rms, 0.0);
    EXPECT_LE(reused.hausdorff, z + 1e-9);
  }
}

TEST(SurfaceDistance, AHintedSearchFindsTheSameNearestPoint) {
  const Mesh mesh = make_bending_cylinder(16, 16);
  const auto soup = posed_soup(mesh, example_poses(mesh)[1]);
  const MeasuredSurface surface(soup, 0, 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::uniform_int_distribution<int> any(-2, int(soup.triangles.size()) + 2);  // out-of-range hints too
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d q(u(rng), u(rng), u(rng) + 1.0);
    int plain = -1, hinted = -1;
    const double d = surface.distance(q, plain);
    const double dh = surface.distance(q, hinted, any(rng));
    EXPECT_EQ(dh, d);
    ASSERT_GE(hinted, 0);
    EXPECT_EQ(hinted, plain);  // ties (a point nearest to an edge) go to the lower index either way
    const auto& t = soup.triangles[hinted];
    const Eigen::Vector3d c[3] = {soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]};
    Eigen::Vector3d bary;
    EXPECT_NEAR(std::sqrt(closest_barycentric(c, q, bary)), d, 1e-9);
  }
}

// Hints from the previous frame change how fast the nearest points are found, never which: the numbers
// equal the unhinted ones frame after frame, and every vertex gets its hint.
TEST(SurfaceDistance, HintsFromTheLastFrameGiveTheSameNumbers) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 6);
  Mesh lod = original;
  omsk_test::decimate(lod, 0.2);
  std::vector<int> original_hints, lod_hints;
  for (double t : {0.1, 0.2, 0.45, 0.8}) {
    const Pose p = sample_pose(skeleton(original), clips(original)[0], t * clips(original)[0].duration);
    const MeasuredSurface a(posed_soup(original, p), 3000, 1), b(posed_soup(lod, p), 3000, 2);
    const SurfaceDistance plain = surface_distance(a, b), hinted = surface_distance(a, b, original_hints, lod_hints);
    EXPECT_EQ(hinted.samples, plain.samples);
    EXPECT_EQ(hinted.rms, plain.rms) << "t " << t;  // bit for bit
    EXPECT_EQ(hinted.hausdorff, plain.hausdorff) << "t " << t;
    EXPECT_GT(original_hints.size(), lod_hints.size());  // one per vertex a face uses
    EXPECT_LE(original_hints.size(), original.n_vertices());
    EXPECT_TRUE(std::all_of(original_hints.begin(), original_hints.end(),
                            [&](int h) { return h >= 0 && size_t(h) < lod.n_faces(); }));
  }
}

// A dense original (Testwuson subdivided once: 7,440 vertices) with only some of its vertices counted toward
// the RMS: the RMS stays close to the one every vertex gives, and the Hausdorff distance is the same to the
// bit though most vertices were never searched.
TEST(SurfaceDistance, CountingSomeVerticesKeepsTheHausdorffExactAndTheRmsClose) {
  const Mesh original = loop_subdivide(omsk_test::load_character("X/Testwuson.X", 6));
  Mesh lod = original;
  omsk_test::decimate(lod, 0.02);
  std::vector<int> all_hints, all_lod_hints, some_hints, some_lod_hints, few_hints, few_lod_hints;
  bool worst_is_a_vertex = false;
  for (double t : {0.1, 0.3, 0.55, 0.8}) {
    const Pose p = sample_pose(skeleton(original), clips(original)[0], t * clips(original)[0].duration);
    const MeasuredSurface a(posed_soup(original, p), 3000, 1), b(posed_soup(lod, p), 3000, 2);
    const SurfaceDistance all = surface_distance(a, b, all_hints, all_lod_hints);
    const SurfaceDistance some = surface_distance(a, b, some_hints, some_lod_hints, 1500);
    const SurfaceDistance few = surface_distance(a, b, few_hints, few_lod_hints, 60);
    EXPECT_EQ(surface_distance(a, b).hausdorff, all.hausdorff);
    EXPECT_EQ(some.hausdorff, all.hausdorff) << "t " << t;
    EXPECT_EQ(few.hausdorff, all.hausdorff) << "t " << t;
    EXPECT_NEAR(some.rms, all.rms, 0.02 * all.rms) << "t " << t;
    EXPECT_EQ(some.samples, all.samples);  // the measured vertices stand for the others
    // Only counted vertices are sure to have been searched; the others keep their hints from whenever they were.
    EXPECT_TRUE(std::all_of(few_hints.begin(), few_hints.end(), [&](int h) { return h < int(lod.n_faces()); }));
    // The test means something where the worst sample is one of the original's vertices (of which only
    // one in 124 counts): then only the bounded search found it.
    double worst_vertex = 0.0;
    for (const auto& q : posed_soup(original, p).points) worst_vertex = std::max(worst_vertex, b.distance(q));
    worst_is_a_vertex |= worst_vertex == all.hausdorff;
  }
  EXPECT_TRUE(worst_is_a_vertex);
}

// A cap at or above the vertex count changes nothing.
TEST(SurfaceDistance, ACapAboveTheVertexCountGivesTheSameNumbers) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 6);
  Mesh lod = original;
  omsk_test::decimate(lod, 0.2);
  const Pose p = sample_pose(skeleton(original), clips(original)[1], 0.37);
  const MeasuredSurface a(posed_soup(original, p), 3000, 1), b(posed_soup(lod, p), 3000, 2);
  std::vector<int> h1, h2, h3, h4;
  const SurfaceDistance all = surface_distance(a, b, h1, h2), capped = surface_distance(a, b, h3, h4, 1000000);
  EXPECT_EQ(capped.rms, all.rms);
  EXPECT_EQ(capped.hausdorff, all.hausdorff);
  EXPECT_EQ(capped.samples, all.samples);
  EXPECT_EQ(h3, h1);
}

// The held-out measure on two threads gives the numbers one thread gives, to the bit, where only some of the
// original's vertices count toward the RMS (which ones follows the hierarchy's leaf order, so every thread
// must build its hierarchy in the same frame, whichever frame it takes first).
TEST(Evaluate, TheNumbersDoNotDependOnTheThreads) {
  const Mesh original = loop_subdivide(omsk_test::load_character("X/Testwuson.X", 6));
  Mesh lod = original;
  omsk_test::decimate(lod, 0.05);
  std::vector<Pose> frames;
  for (int i = 0; i < 8; ++i)
    frames.push_back(sample_pose(skeleton(original), clips(original)[0], (i + 0.5) / 8 * clips(original)[0].duration));
  EvaluateOptions one;
  one.threads = 1;
  one.samples = 2000;
  one.counted_vertices = 500;
  const HeldOutError alone = evaluate(original, lod, frames, one);
  EvaluateOptions two = one;
  two.threads = 2;
  for (int run = 0; run < 4; ++run) {
    const HeldOutError shared = evaluate(original, lod, frames, two);
    EXPECT_EQ(shared.rms, alone.rms) << "run " << run;
    EXPECT_EQ(shared.hausdorff, alone.hausdorff) << "run " << run;
  }
}
