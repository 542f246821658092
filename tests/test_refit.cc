// The final fit: LOD rest positions re-optimised against the original surface in every example pose.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Solver/Refit.hh>

#include <random>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

std::vector<Pose> heldout_poses(const Mesh& m) {
  std::vector<Pose> held;
  const Clip& c = clips(m)[0];
  for (int i = 0; i < 7; ++i) held.push_back(sample_pose(skeleton(m), c, c.duration * (i + 0.5) / 8));
  return held;
}

double mean_rms(const Mesh& original, const Mesh& lod, const std::vector<Pose>& poses) {
  double sum = 0.0;
  for (const Pose& p : poses) sum += omsk_test::posed_rms(original, lod, p);
  return sum / poses.size();
}

// \p original decimated to \p faces by the skinned modules under the lazy driver, garbage-collected.
Mesh decimated(const Mesh& original, size_t faces) {
  Mesh lod = original;
  {
    LazyDecimaterT<Mesh> dec(lod);
    omsk_test::SkinnedModules<LazyDecimaterT<Mesh>> m(dec);
    EXPECT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, faces);
  }
  lod.garbage_collection();
  return lod;
}

// fitted[i] refitted against \p original in its example poses with settings s[i].
void fit_both(const Mesh& original, const RefitSettings (&s)[2], Mesh (&fitted)[2], RefitReport (&r)[2]) {
  for (int i = 0; i < 2; ++i) r[i] = refit_positions(fitted[i], original, example_poses(original), s[i]);
}

}  // namespace

TEST(Refit, PutsAShakenCopyBackOnTheSurface) {
  // The original itself with its vertices shaken: the fit must pull them back onto the surface.
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 6);
  Mesh shaken = original;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.002 * bbox_diagonal(original));
  for (auto vh : shaken.vertices()) {
    auto p = shaken.point(vh);
    shaken.set_point(vh, p + Mesh::Point(noise(rng), noise(rng), noise(rng)));
  }
  const auto poses = example_poses(original);
  const double before = mean_rms(original, shaken, poses);
  const RefitReport r = refit_positions(shaken, original, poses);
  const double after = mean_rms(original, shaken, poses);
  EXPECT_EQ(r.rounds, 3);
  EXPECT_LT(r.after, r.before);
  EXPECT_LT(after, 0.75 * before) << before << " -> " << after;  // measured 0.65x: folds vs the shaken faces limit it
}

TEST(Refit, LowersTheErrorOfADecimatedCharacterInFramesItNeverSaw) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 10);
  const auto held = heldout_poses(original);
  const double before = mean_rms(original, lod, held);
  Mesh fitted = lod;
  refit_positions(fitted, original, example_poses(original));
  const double after = mean_rms(original, fitted, held);
  std::printf("held-out RMS at 10%%: %.5f before the fit, %.5f after\n", before, after);
  EXPECT_LT(after, 0.95 * before);
  // Only rest positions and skin weights moved: same faces, valid skins within the cap, no face turned over
  // in any example pose.
  ASSERT_EQ(fitted.n_faces(), lod.n_faces());
  const auto h = influences_handle(lod);
  int cap = 1;  // the LOD's own, which the fit keeps by default
  for (auto vh : lod.vertices()) cap = std::max(cap, lod.property(h, vh).size());
  for (auto vh : lod.vertices()) {
    EXPECT_LE(fitted.property(h, vh).size(), cap);
    EXPECT_NEAR(fitted.property(h, vh).sum(), 1.0, 1e-9);
  }
  for (const Pose& p : example_poses(original)) {
    const auto a = skin_face_normals(lod, skin_positions(lod, p)),
               b = skin_face_normals(fitted, skin_positions(fitted, p));
    for (auto fh : lod.faces()) {
      if (a[fh.idx()].squaredNorm() > 0.0) {
        EXPECT_GT(a[fh.idx()].dot(b[fh.idx()]), 0.0);
      }
    }
  }
}

// Weighing a sample's residual less along the LOD's surface lets the fit slide there, toward where the
// samples' nearest points settle: in the same three rounds it lies closer in frames it never saw.
TEST(Refit, SlidingAlongTheSurfaceFitsCloserInTheSameRounds) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 4);
  const auto held = heldout_poses(original);
  RefitSettings s[2];
  s[0].tangential_weight = 1.0;  // point to point
  ASSERT_LT(s[1].tangential_weight, 1.0);
  Mesh fitted[2] = {lod, lod};
  RefitReport r[2];
  fit_both(original, s, fitted, r);
  EXPECT_EQ(r[0].rounds, r[1].rounds);
  const double point = mean_rms(original, fitted[0], held), sliding = mean_rms(original, fitted[1], held);
  std::printf("held-out RMS at 25%%: %.6f point to point, %.6f sliding\n", point, sliding);
  EXPECT_LT(sliding, point);
}

// A pass anchors the LOD's vertices to the original where the pass starts; the next pass, anchored where the
// last one left them, fits closer again (make_lods runs three on small inputs).
TEST(Refit, APassFromWhereTheLastLeftFitsCloser) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 4);
  const auto held = heldout_poses(original);
  Mesh once = lod;
  refit_positions(once, original, example_poses(original));
  Mesh twice = once;
  const RefitReport again = refit_positions(twice, original, example_poses(original));
  EXPECT_GT(again.rounds, 0);
  const double a = mean_rms(original, once, held), b = mean_rms(original, twice, held);
  std::printf("held-out RMS at 25%%: %.6f after one pass, %.6f after two\n", a, b);
  EXPECT_LT(b, a);
}

namespace {

// RMS distance from points spread by area over the posed LOD to the posed original, over \p poses: the half
// of the symmetric held-out measure that the LOD's vertices alone do not see.
double lod_to_original_rms(const Mesh& original, const Mesh& lod, const std::vector<Pose>& poses) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0.0;
  size_t n = 0;
  for (const Pose& p : poses) {
    const MeasuredSurface target(posed_soup(original, p), 0, 1);
    const TriangleSoup s = posed_soup(lod, p);
    for (const auto& t : s.triangles) {
      const Eigen::Vector3d a = s.points[t[0]], b = s.points[t[1]], c = s.points[t[2]];
      const int k = 1 + int(2000.0 * (b - a).cross(c - a).norm() / bbox_diagonal(original) / bbox_diagonal(original));
      for (int i = 0; i < k; ++i) {
        double r1 = u(rng), r2 = u(rng);
        if (r1 + r2 > 1.0) {
          r1 = 1.0 - r1;
          r2 = 1.0 - r2;
        }
        const double d = target.distance(a + r1 * (b - a) + r2 * (c - a));
        sum += d * d;  // a face's points are as many as its area allows: it weighs by its area
        ++n;
      }
    }
  }
  return std::sqrt(sum / double(n));
}

}  // namespace

// The held-out measure is symmetric, and a coarse LOD's faces can leave the original between vertices that
// sit on it: drawing points of the faces to the original as well brings the LOD's surface closer to it,
// and the symmetric RMS with it, in frames the fit never saw.
TEST(Refit, TheLodsFacesDrawnToTheOriginalBringItsSurfaceCloser) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 10);
  const auto held = heldout_poses(original);
  RefitSettings s[2];
  s[0].face_weight = 0.0;  // the LOD's vertices alone
  ASSERT_GT(s[1].face_weight, 0.0);
  Mesh fitted[2] = {lod, lod};
  RefitReport r[2];
  fit_both(original, s, fitted, r);
  const double faces[2] = {lod_to_original_rms(original, fitted[0], held),
                           lod_to_original_rms(original, fitted[1], held)};
  const double rms[2] = {mean_rms(original, fitted[0], held), mean_rms(original, fitted[1], held)};
  std::printf("held-out at 10%%, vertices alone / with the faces: RMS %.6f / %.6f, LOD to original %.6f / %.6f\n",
              rms[0], rms[1], faces[0], faces[1]);
  EXPECT_LT(faces[1], 0.985 * faces[0]);  // measured 0.96
  EXPECT_LT(rms[1], rms[0]);
}

// The decimation chose each merged vertex's weights where it stood before the fit moved it, from its two
// endpoints' joints only: fitting them again with the positions (over the vertex's and its neighbours'
// joints) brings the LOD closer in frames the fit never saw, and leaves a valid skin within the cap.
TEST(Refit, FittingTheSkinWeightsLowersTheHeldOutError) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 10);
  const auto held = heldout_poses(original);
  RefitSettings s[2];
  s[0].fit_weights = false;
  ASSERT_TRUE(s[1].fit_weights);
  s[1].max_influences = 4;
  Mesh fitted[2] = {lod, lod};
  RefitReport r[2];
  fit_both(original, s, fitted, r);
  const double rms[2] = {mean_rms(original, fitted[0], held), mean_rms(original, fitted[1], held)};
  std::printf("held-out at 10%%, positions alone / with the weights: RMS %.6f / %.6f\n", rms[0], rms[1]);
  EXPECT_LT(rms[1], rms[0]);
  const auto h = influences_handle(fitted[1]);
  size_t changed = 0;
  for (auto vh : fitted[1].vertices()) {
    const Influences& inf = fitted[1].property(h, vh);
    changed += inf != fitted[0].property(h, vh);
    EXPECT_LE(inf.size(), s[1].max_influences);
    EXPECT_NEAR(inf.sum(), 1.0, 1e-9);
    for (const JointWeight& jw : inf) EXPECT_GT(jw.weight, 0.0);
  }
  EXPECT_GT(changed, fitted[1].n_vertices() / 4);
  // Without a cap of its own the fit keeps the LOD's: a LOD capped at two influences stays so.
  Mesh two = lod;
  for (auto vh : two.vertices()) two.property(h, vh).keep_heaviest(2);
  refit_positions(two, original, example_poses(original));
  for (auto vh : two.vertices()) EXPECT_LE(two.property(h, vh).size(), 2);
  s[1].max_influences = 9;
  EXPECT_THROW(refit_positions(fitted[1], original, example_poses(original), s[1]), std::invalid_argument);
}

TEST(Refit, RefusesAFaceWeightOrSplitOutOfRange) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 4);
  for (const double w : {-1.0, double(NAN), double(INFINITY)}) {
    Mesh copy = original;
    RefitSettings s;
    s.face_weight = w;
    EXPECT_THROW(refit_positions(copy, original, example_poses(original), s), std::invalid_argument) << w;
  }
  Mesh copy = original;
  RefitSettings s;
  s.face_split = 0;
  EXPECT_THROW(refit_positions(copy, original, example_poses(original), s), std::invalid_argument);
}

TEST(Refit, RefusesATangentialWeightOutsideZeroToOne) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 4);
  for (const double t : {0.0, -0.5, 1.5}) {
    Mesh copy = original;
    RefitSettings s;
    s.tangential_weight = t;
    EXPECT_THROW(refit_positions(copy, original, example_poses(original), s), std::invalid_argument) << t;
  }
}

TEST(Refit, NothingToFitIsNoChange) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 4);
  Mesh copy = original;
  const RefitReport r = refit_positions(copy, original, {});
  EXPECT_EQ(r.rounds, 0);
  omsk_test::expect_same_mesh(copy, original);
}

TEST(Refit, TheAnswerDoesNotDependOnTheThreadCount) {
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 5);
  RefitSettings s[2];
  s[1].threads = 3;
  Mesh fitted[2] = {lod, lod};
  RefitReport r[2];
  fit_both(original, s, fitted, r);
  EXPECT_GT(r[0].rounds, 0);
  EXPECT_EQ(r[0].after, r[1].after);
  omsk_test::expect_same_mesh(fitted[0], fitted[1]);
}

TEST(Refit, ASliverThatTurnsOverAtAnyStepDoesNotHoldTheRestBack) {
  // One face of a decimated Testwuson made a sliver: its apex moved to within 1e-9 of the line through the
  // other two corners, on one side or the other. Whichever way the fit moves the corners, on one of the two
  // sides the face turns over at any step; the fit then holds that face's corners and moves the others.
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 10);
  int runs = 0;
  for (auto fh : lod.faces()) {
    if (runs == 6) break;
    if (fh.idx() % 50 != 0) continue;
    for (double side : {1.0, -1.0}) {
      Mesh trial = lod;
      auto it = trial.fv_range(fh).begin();
      const auto va = *it, vb = *++it, vc = *++it;
      const Eigen::Vector3d a = to_eigen(trial.point(va)), b = to_eigen(trial.point(vb)), c = to_eigen(trial.point(vc));
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized(), in_plane = n.cross(b - a).normalized();
      const Eigen::Vector3d apex = a + (c - a).dot(b - a) / (b - a).squaredNorm() * (b - a) + side * 1e-9 * in_plane;
      trial.set_point(vc, Mesh::Point(apex.x(), apex.y(), apex.z()));
      std::vector<Eigen::Vector3d> before;
      for (auto vh : trial.vertices()) before.push_back(to_eigen(trial.point(vh)));
      const RefitReport r = refit_positions(trial, original, example_poses(original));
      ++runs;
      EXPECT_EQ(r.rounds, 3) << "face " << fh.idx() << ", side " << side;
      EXPECT_LT(r.after, r.before);
      int moved = 0;
      for (auto vh : trial.vertices()) moved += (to_eigen(trial.point(vh)) - before[vh.idx()]).norm() > 0.0;
      EXPECT_GT(moved, int(trial.n_vertices()) / 2);
    }
  }
  EXPECT_EQ(runs, 6);
}

TEST(Refit, ConjugateGradientsTakeTheFactorizationsStep) {
  // Large LODs take their steps from conjugate gradients: the fit must land where the factorization's does.
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const Mesh lod = decimated(original, original.n_faces() / 5);
  RefitSettings s[2];
  s[0].direct_max_vertices = lod.n_vertices();
  s[1].direct_max_vertices = 0;
  Mesh fitted[2] = {lod, lod};
  RefitReport r[2];
  fit_both(original, s, fitted, r);
  EXPECT_EQ(r[0].rounds, r[1].rounds);
  EXPECT_LT(r[0].after, r[0].before);
  EXPECT_NEAR(r[1].after, r[0].after, 1e-6 * r[0].after);
  const double tol = 1e-7 * bbox_diagonal(original);
  for (auto vh : lod.vertices()) EXPECT_LT((fitted[0].point(vh) - fitted[1].point(vh)).norm(), tol) << vh.idx();
}
