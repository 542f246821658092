// Edge flips after decimation: a diagonal across a ridge turns onto it, seams and folds stay, and a real
// character's LOD lies closer to the original in held-out frames.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Solver/EdgeFlipFit.hh>
#include <OpenMeshSkinned/Solver/Refit.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// The diamond's corners (s, t) in {0, 1}^2: x = s + t, y = 1 - s + t, on the roof z = h (1 - |x - 1|), whose
// ridge x = 1 joins (1, 0) and (1, 2).
Mesh::Point roof(double s, double t, double h) {
  const double x = s + t;
  return Mesh::Point(x, 1.0 - s + t, h * (1.0 - std::abs(x - 1.0)));
}

void rigid_on_one_joint(Mesh& mesh) {
  const auto h = add_skin(mesh);
  Skeleton skel;
  skel.joints.push_back(Joint{"root"});
  skeleton(mesh) = skel;
  for (auto vh : mesh.vertices()) {
    Influences w;
    w.push(0, 1.0);
    mesh.property(h, vh) = w;
  }
}

// Each corner's UV from its vertex's position, normal +z: no seam anywhere.
void smooth_corners(Mesh& mesh) {
  for (auto fh : mesh.faces())
    for (auto h : mesh.fh_range(fh)) {
      const auto p = mesh.point(mesh.to_vertex_handle(h));
      mesh.set_texcoord2D(h, Mesh::TexCoord2D(p[0] / 2, p[1] / 2));
      mesh.set_normal(h, Mesh::Normal(0, 0, 1));
    }
}

// The roof over the diamond, n x n squares cut along s + t = const (so that the ridge is an edge line).
Mesh fine_roof(int n, double h) {
  Mesh mesh;
  request_skinned_attributes(mesh);
  std::vector<Mesh::VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(mesh.add_vertex(roof(double(i) / n, double(j) / n, h)));
  auto at = [&](int i, int j) { return v[j * (n + 1) + i]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.add_face(at(i, j), at(i + 1, j), at(i, j + 1));
      mesh.add_face(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  rigid_on_one_joint(mesh);
  smooth_corners(mesh);
  return mesh;
}

// The diamond as two faces joined across the ridge: the diagonal from (0, 1, 0) to (2, 1, 0).
Mesh coarse_roof(double h) {
  Mesh mesh;
  request_skinned_attributes(mesh);
  const auto p00 = mesh.add_vertex(roof(0, 0, h)), p10 = mesh.add_vertex(roof(1, 0, h)),
             p11 = mesh.add_vertex(roof(1, 1, h)), p01 = mesh.add_vertex(roof(0, 1, h));
  mesh.add_face(p00, p10, p11);
  mesh.add_face(p00, p11, p01);
  rigid_on_one_joint(mesh);
  smooth_corners(mesh);
  return mesh;
}

// The one interior edge's end vertices' x, sorted.
std::pair<double, double> diagonal_x(const Mesh& mesh) {
  for (auto eh : mesh.edges())
    if (!mesh.is_boundary(eh)) {
      const double a = mesh.point(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)))[0];
      const double b = mesh.point(mesh.to_vertex_handle(mesh.halfedge_handle(eh, 0)))[0];
      return {std::min(a, b), std::max(a, b)};
    }
  return {-1.0, -1.0};
}

const std::vector<Pose> kRest = {Pose::identity(1)};

}  // namespace

TEST(EdgeFlipFit, TurnsADiagonalAcrossARidgeOntoIt) {
  const Mesh original = fine_roof(8, 0.3);
  Mesh lod = coarse_roof(0.3);
  ASSERT_EQ(diagonal_x(lod), std::make_pair(0.0, 2.0));
  const double before = surface_distance(posed_soup(original, kRest[0]), posed_soup(lod, kRest[0]), 4000).rms;
  const FlipFitReport r = flip_edges_to_fit(lod, original, kRest);
  EXPECT_EQ(r.flips, 1);
  EXPECT_LT(r.after, r.before);
  EXPECT_EQ(diagonal_x(lod), std::make_pair(1.0, 1.0));  // the ridge
  // Both faces now lie on the roof's two planes.
  EXPECT_LT(surface_distance(posed_soup(original, kRest[0]), posed_soup(lod, kRest[0]), 4000).rms, 1e-9);
  EXPECT_GT(before, 0.01);
  // Orientation and corners: both faces face up, every corner keeps its vertex's UV.
  for (auto fh : lod.faces()) {
    auto fv = lod.cfv_iter(fh);
    const auto a = lod.point(*fv++), b = lod.point(*fv++), c = lod.point(*fv);
    EXPECT_GT(((b - a) % (c - a))[2], 0.0);
    for (auto h : lod.fh_range(fh)) {
      const auto p = lod.point(lod.to_vertex_handle(h));
      EXPECT_FLOAT_EQ(lod.texcoord2D(h)[0], float(p[0] / 2));
      EXPECT_FLOAT_EQ(lod.texcoord2D(h)[1], float(p[1] / 2));
    }
  }
}

TEST(EdgeFlipFit, LeavesAFlatQuadAlone) {
  // On a flat original both diagonals fit exactly: no flip gains.
  const Mesh original = fine_roof(8, 0.0);
  Mesh lod = coarse_roof(0.0);
  EXPECT_EQ(flip_edges_to_fit(lod, original, kRest).flips, 0);
  EXPECT_EQ(diagonal_x(lod), std::make_pair(0.0, 2.0));
}

TEST(EdgeFlipFit, KeepsAUvSeam) {
  const Mesh original = fine_roof(8, 0.3);
  Mesh lod = coarse_roof(0.3);
  // One face's corner at an end of the diagonal in another chart: the edge is a seam there.
  for (auto h : lod.fh_range(*lod.faces().begin()))
    if (lod.point(lod.to_vertex_handle(h))[0] == 0.0) lod.set_texcoord2D(h, Mesh::TexCoord2D(5, 5));
  EXPECT_EQ(flip_edges_to_fit(lod, original, kRest).flips, 0);
  EXPECT_EQ(diagonal_x(lod), std::make_pair(0.0, 2.0));
}

TEST(EdgeFlipFit, KeepsAMaterialBoundary) {
  const Mesh original = fine_roof(8, 0.3);
  Mesh lod = coarse_roof(0.3);
  const auto hm = face_material_handle(lod);
  lod.property(hm, *lod.faces().begin()) = 1;
  EXPECT_EQ(flip_edges_to_fit(lod, original, kRest).flips, 0);
}

TEST(EdgeFlipFit, RefusesAFlipThatFoldsTheFaces) {
  // A ridge so steep that the diagonal along it joins faces more than 90 degrees apart.
  const Mesh original = fine_roof(8, 3.0);
  Mesh lod = coarse_roof(3.0);
  EXPECT_EQ(flip_edges_to_fit(lod, original, kRest).flips, 0);
}

// Testwuson decimated to 900 faces and fitted: a LOD with flips to find.
struct Decimated {
  Mesh original, lod;
};
const Decimated& decimated_wuson() {
  static const Decimated d = [] {
    Decimated out{omsk_test::load_character("X/Testwuson.X", 6), Mesh()};
    out.lod = out.original;
    {
      LazyDecimaterT<Mesh> dec(out.lod);
      omsk_test::SkinnedModules<LazyDecimaterT<Mesh>> m(dec);
      if (!dec.initialize()) {
        ADD_FAILURE() << "the decimater did not initialise";
        return out;
      }
      dec.decimate_to_faces(0, 900);
    }
    out.lod.garbage_collection();
    refit_positions(out.lod, out.original, example_poses(out.original));
    return out;
  }();
  return d;
}

// Mean RMS over five frames of the first clip that are not example poses.
double held_out_rms(const Mesh& original, const Mesh& lod) {
  const Clip& c = clips(original)[0];
  double sum = 0.0;
  for (int i = 0; i < 5; ++i)
    sum += omsk_test::posed_rms(original, lod, sample_pose(skeleton(original), c, c.duration * (i + 0.5) / 6));
  return sum / 5.0;
}

TEST(EdgeFlipFit, BringsADecimatedCharacterCloserInHeldOutFrames) {
  const auto& [original, lod] = decimated_wuson();
  const auto& poses = example_poses(original);
  Mesh flipped = lod;
  const FlipFitReport r = flip_edges_to_fit(flipped, original, poses);
  EXPECT_GT(r.flips, 0);
  EXPECT_LT(r.after, r.before);
  refit_positions(flipped, original, poses);
  EXPECT_EQ(flipped.n_faces(), lod.n_faces());
  omsk_test::expect_valid_skin(flipped, 4);
  EXPECT_LT(held_out_rms(original, flipped), 0.99 * held_out_rms(original, lod));
}

// Poses are dealt to threads in turn but summed in pose order: the same flips on any thread count.
TEST(EdgeFlipFit, FlipsTheSameEdgesOnAnyThreadCount) {
  const auto& [original, lod] = decimated_wuson();
  Mesh one = lod, three = lod;
  FlipFitSettings s;
  s.threads = 1;
  const FlipFitReport r1 = flip_edges_to_fit(one, original, example_poses(original), s);
  s.threads = 3;
  const FlipFitReport r3 = flip_edges_to_fit(three, original, example_poses(original), s);
  ASSERT_GT(r1.flips, 0);
  EXPECT_EQ(r1.flips, r3.flips);
  EXPECT_EQ(r1.after, r3.after);
  for (auto fh : one.faces()) {
    auto a = one.fv_begin(fh), b = three.fv_begin(fh);
    for (int k = 0; k < 3; ++k, ++a, ++b) ASSERT_EQ(a->idx(), b->idx()) << "face " << fh.idx();
  }
}

// The screen settles most edges in a few poses; what it lets through is judged in all of them, so the LOD
// fits as well as one judged on every edge in every pose.
TEST(EdgeFlipFit, TheScreenKeepsTheFlipsThatFit) {
  const auto& [original, lod] = decimated_wuson();
  const auto& poses = example_poses(original);
  ASSERT_GT(poses.size(), 4u);
  Mesh screened = lod, full = lod;
  FlipFitSettings s;
  const FlipFitReport rs = flip_edges_to_fit(screened, original, poses, s);
  s.screen_poses = 0;
  const FlipFitReport rf = flip_edges_to_fit(full, original, poses, s);
  ASSERT_GT(rf.flips, 0);
  EXPECT_GE(rs.flips, rf.flips * 9 / 10);
  refit_positions(screened, original, poses);
  refit_positions(full, original, poses);
  EXPECT_LT(held_out_rms(original, screened), 1.005 * held_out_rms(original, full));
}
