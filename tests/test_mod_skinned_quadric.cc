#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/SolverSettings.hh>

#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <cmath>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(ModSkinnedQuadric, BeatsStaticQuadricInAHeldOutPoseOnTheBendingLeg) {
  // Example poses: knee at 0 and 90 degrees. Held out: 45 degrees.
  const Mesh original = make_bending_cylinder(32, 64);
  const Pose held_out = sample_pose(skeleton(original), clips(original)[0], 0.5);

  Mesh skinned = original;
  omsk_test::Modules only_quadric;
  only_quadric.cap = only_quadric.fold = false;
  omsk_test::decimate(skinned, 0.05, only_quadric);

  // The industry baseline: OpenMesh's static quadric in the rest pose; the surviving vertex keeps its
  // own position and weights (halfedge collapse).
  Mesh stat = original;
  {
    OpenMesh::Decimater::DecimaterT<Mesh> dec(stat);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
    dec.add(hq);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, static_cast<size_t>(0.05 * stat.n_faces()));
    stat.garbage_collection();
  }
  ASSERT_NEAR(double(skinned.n_faces()), double(stat.n_faces()), 0.02 * original.n_faces());
  const double e_skinned = omsk_test::posed_rms(original, skinned, held_out);
  const double e_static = omsk_test::posed_rms(original, stat, held_out);
  ::testing::Test::RecordProperty("heldout_rms_skinned", std::to_string(e_skinned));
  ::testing::Test::RecordProperty("heldout_rms_static", std::to_string(e_static));
  EXPECT_LT(e_skinned, e_static) << "skinned " << e_skinned << " vs static " << e_static;
}

TEST(ModSkinnedQuadric, InfiniteToleranceIsTheSameAsNoTolerance) {
  Mesh a = omsk_test::load_character("X/Testwuson.X", 4);
  Mesh b = a;
  omsk_test::decimate(a, 0.3);
  {
    OpenMesh::Decimater::DecimaterT<Mesh> dec(b);
    ModSkinnedQuadricT<Mesh>::Handle hq;
    ModWeightCapT<Mesh>::Handle hc;
    ModSkinnedFoldOverT<Mesh>::Handle hf;
    omsk_test::FlipWatcherT<Mesh>::Handle hw;
    dec.add(hq);
    dec.add(hc);
    dec.add(hf);
    dec.add(hw);
    dec.module(hq).set_max_err(1e300);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, static_cast<size_t>(0.3 * b.n_faces()));
    b.garbage_collection();
  }
  ASSERT_EQ(a.n_faces(), b.n_faces());
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  for (auto vh : a.vertices()) EXPECT_EQ(a.point(vh), b.point(vh));
}

TEST(ModSkinnedQuadric, ZeroToleranceOnACurvedCharacterRefusesEveryCollapse) {
  // Every collapse on a closed, everywhere-curved surface costs something: a zero tolerance is stuck.
  Mesh mesh = make_bending_cylinder(16, 16);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  dec.module(hq).set_max_err(0.0);
  ASSERT_TRUE(dec.initialize());
  // Edges along the tube are straight in the rest pose but bend at the knee in the 90 degree pose; edges
  // around it are curved in every pose. Only edges far from the knee along the axis may be free.
  const size_t before = mesh.n_faces();
  dec.decimate_to_faces(0, before / 10);
  mesh.garbage_collection();
  Mesh free_mesh = make_bending_cylinder(16, 16);
  omsk_test::Modules only_quadric;
  only_quadric.cap = only_quadric.fold = false;
  omsk_test::decimate(free_mesh, 0.1, only_quadric);
  EXPECT_GT(mesh.n_faces(), 2 * free_mesh.n_faces());
}

TEST(ModSkinnedQuadric, InvariantsAfterDecimatingARealCharacterToTenPercent) {
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 8);
  const auto r = omsk_test::decimate(mesh, 0.1);
  EXPECT_LE(r.faces_after, static_cast<size_t>(0.12 * r.faces_before));
  EXPECT_EQ(r.flipped, 0u) << "collapses that turned a face by more than 90 degrees in some pose (forced " << r.forced
                           << ", fallbacks " << r.fallbacks << ")";
  omsk_test::expect_valid_skin(mesh, 4);
}

TEST(ModSkinnedQuadric, MovesTheSurvivorAndGivesItSolvedWeights) {
  Mesh mesh = make_bending_cylinder(16, 32);
  const Mesh original = mesh;
  omsk_test::Modules only_quadric;
  only_quadric.cap = only_quadric.fold = false;
  omsk_test::decimate(mesh, 0.2, only_quadric);
  // Some surviving vertices sit where no input vertex was (optimal placement, not endpoint placement),
  // and some carry weights no input vertex had.
  size_t moved = 0, new_weights = 0;
  const auto h = influences_handle(mesh);
  for (auto vh : mesh.vertices()) {
    bool found = false, same_w = false;
    for (auto ov : original.vertices()) {
      found |= (original.point(ov) - mesh.point(vh)).norm() < 1e-12;
      same_w |= original.property(h, ov) == mesh.property(h, vh);
    }
    moved += !found;
    new_weights += !same_w;
  }
  EXPECT_GT(moved, 0u);
  EXPECT_GT(new_weights, 0u);
}

TEST(ModSkinnedQuadric, MovedVerticesKeepTheirTextureMapping) {
  // A bumpy sheet whose UVs are its (x, y): wherever a vertex moves, its corners must read the UV of the
  // place it moved to, interpolated from the faces it came from.
  Mesh mesh;
  request_skinned_attributes(mesh);
  const auto h = add_skin(mesh);
  Joint j;
  j.name = "root";
  skeleton(mesh).joints = {j};
  const int n = 24;
  std::vector<Mesh::VertexHandle> vh;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double x = double(k) / n, y = double(i) / n;
      vh.push_back(mesh.add_vertex(Mesh::Point(x, y, 0.05 * std::sin(6.0 * x) * std::cos(5.0 * y))));
      mesh.property(h, vh.back()) = Influences::rigid(0);
    }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const auto a = vh[i * (n + 1) + k], b = vh[i * (n + 1) + k + 1], c = vh[(i + 1) * (n + 1) + k],
                 d = vh[(i + 1) * (n + 1) + k + 1];
      mesh.add_face(a, b, d);
      mesh.add_face(a, d, c);
    }
  clear_corner_attributes(mesh);  // the normals: OpenMesh leaves them uninitialised
  for (auto heh : mesh.halfedges()) {
    const auto p = mesh.point(mesh.to_vertex_handle(heh));
    mesh.set_texcoord2D(heh, Mesh::TexCoord2D(float(p[0]), float(p[1])));
  }
  example_poses(mesh) = {Pose::identity(1)};
  omsk_test::Modules only_quadric;
  only_quadric.cap = only_quadric.fold = false;
  omsk_test::decimate(mesh, 0.2, only_quadric);
  size_t corners = 0;
  double worst = 0.0;
  for (auto heh : mesh.halfedges()) {
    if (mesh.is_boundary(heh)) continue;
    const auto p = mesh.point(mesh.to_vertex_handle(heh));
    const auto t = mesh.texcoord2D(heh);
    worst = std::max(worst, std::hypot(t[0] - p[0], t[1] - p[1]));
    ++corners;
  }
  EXPECT_GT(corners, 100u);
  // UVs are linear in x, y on every original face, so interpolation is exact up to how far the vertex
  // left the original surface (the bumps are 0.05 high).
  ::testing::Test::RecordProperty("worst_uv_error", std::to_string(worst));
  EXPECT_LT(worst, 0.005);
}

template <typename Driver>
void per_area_against_energy() {
  // Testwuson to 25%: the paper's energy makes the horn tips cheap (small faces, far from the rest); per
  // area they cost their distance. Judged in frames the decimater never saw.
  using namespace OpenMeshSkinned;
  const Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  std::vector<Pose> held;
  for (int i = 0; i < 7; ++i)
    held.push_back(sample_pose(skeleton(original), clips(original)[0], clips(original)[0].duration * (i + 0.5) / 8));
  auto worst = [&](bool per_area) {
    Mesh mesh = original;
    Driver dec(mesh);
    omsk_test::SkinnedModules<Driver> m(dec);
    dec.module(m.quadric).set_error_per_area(per_area);
    EXPECT_EQ(dec.module(m.quadric).error_per_area(), per_area);
    EXPECT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, original.n_faces() / 4);
    mesh.garbage_collection();
    double h = 0.0;
    for (const Pose& p : held)
      h = std::max(h, surface_distance(posed_soup(original, p), posed_soup(mesh, p), 20000).hausdorff);
    return h / bbox_diagonal(original);
  };
  const double energy = worst(false), per_area = worst(true);
  std::printf("held-out Hausdorff at 25%%: %.4f%% by energy, %.4f%% per area\n", 100 * energy, 100 * per_area);
  EXPECT_LT(per_area, 0.7 * energy);
}

// Under the lazy driver (the tool's). Under DecimaterT, whose stale-verdict handling locks and defers
// vertices, it measured worse at 50% and 25% (ModSkinnedQuadricT.hh).
TEST(ModSkinnedQuadric, PricingPerAreaKeepsTheWorstCaseDownOnARealCharacter) {
  per_area_against_energy<OpenMeshSkinned::LazyDecimaterT<Mesh>>();
}

TEST(ModSkinnedQuadric, AreaExponentAndFloorAreCheckedAndPerAreaIsExponentOne) {
  Mesh mesh = make_bending_cylinder(8, 8);
  LazyDecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  auto& m = dec.module(hq);
  EXPECT_EQ(m.area_exponent(), 0.0);
  m.set_error_per_area(true);
  EXPECT_EQ(m.area_exponent(), 1.0);
  m.set_area_exponent(0.5);
  EXPECT_FALSE(m.error_per_area());
  for (double bad : {-0.01, 1.01, std::nan("")}) EXPECT_THROW(m.set_area_exponent(bad), std::invalid_argument);
  EXPECT_EQ(m.area_exponent(), 0.5);
  for (double bad : {-1.0, HUGE_VAL, std::nan("")}) EXPECT_THROW(m.set_area_floor(bad), std::invalid_argument);
  m.set_area_floor(4.0);
  EXPECT_EQ(m.area_floor(), 4.0);
}

// The arithmetic is area_price's (test_area_price.cc); the solver's settings carry the module's values to it.
TEST(ModSkinnedQuadric, SolverPriorityIsTheAreaPriceOfTheModulesSettings) {
  Mesh mesh = make_bending_cylinder(8, 8);
  LazyDecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  dec.module(hq).set_area_exponent(0.5);
  dec.module(hq).set_area_floor(4.0);
  ASSERT_TRUE(dec.initialize());
  const SolverSettings& s = dec.module(hq).solver().settings();
  CollapseResult r;
  r.error = 8.0;
  for (double area : {16.0, 1.0}) {
    r.area = area;
    EXPECT_EQ(s.priority(r), area_price(8.0, area, 0.5, 4.0));
  }
}
