#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// Six bones, up to six influences, four example poses.
Mesh many_influence_tube() {
  Mesh mesh = omsk_test::many_influence_tube(16, 48);
  example_poses(mesh) = sample_poses_evenly(skeleton(mesh), clips(mesh)[0], 4);
  return mesh;
}

}  // namespace

TEST(ModWeightCap, ReducesInputVerticesAboveTheCapBySolvingNotTruncating) {
  Mesh mesh = many_influence_tube();
  ASSERT_GT(omsk_test::max_influences(mesh), 2);
  const Mesh original = mesh;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  dec.add(hq);
  dec.add(hc);
  dec.module(hc).set_max_influences(2);
  ASSERT_TRUE(dec.initialize());
  EXPECT_GT(dec.module(hc).reduced_vertices(), 0u);
  EXPECT_LE(omsk_test::max_influences(mesh), 2);
  omsk_test::expect_valid_skin(mesh, 2);
  // Solving beats truncation where it matters, the posed surface: in the example poses the reduced mesh
  // stays closer to the original than plain top-2-and-renormalise does.
  Mesh truncated = original;
  const auto h = influences_handle(truncated);
  for (auto vh : truncated.vertices()) truncated.property(h, vh).keep_heaviest(2);
  double err_solved = 0.0, err_truncated = 0.0;
  for (const Pose& pose : example_poses(original)) {
    err_solved += omsk_test::posed_rms(original, mesh, pose);
    err_truncated += omsk_test::posed_rms(original, truncated, pose);
  }
  ::testing::Test::RecordProperty("posed_rms_solved", std::to_string(err_solved));
  ::testing::Test::RecordProperty("posed_rms_truncated", std::to_string(err_truncated));
  EXPECT_LT(err_solved, err_truncated);
}

TEST(ModWeightCap, EveryLevelRespectsTheCap) {
  Mesh mesh = many_influence_tube();
  for (int cap : {1, 2, 3}) {
    Mesh m = mesh;
    omsk_test::Modules mods;
    mods.max_influences = cap;
    const auto r = omsk_test::decimate(m, 0.1, mods);
    EXPECT_LT(r.faces_after, r.faces_before / 5);
    omsk_test::expect_valid_skin(m, cap);
  }
}

TEST(ModWeightCap, StuckWhenEverySurvivorWouldKeepTooManyInfluences) {
  // Unreduced input (two influences everywhere), cap 1, and nothing that places vertices (OpenMesh's own
  // quadric is the priority): every surviving vertex would keep two influences, so nothing collapses.
  Mesh mesh = make_bending_cylinder(16, 16);
  const auto h = influences_handle(mesh);
  for (auto vh : mesh.vertices()) {
    Influences inf;
    inf.push(0, 0.5);
    inf.push(1, 0.5);
    mesh.property(h, vh) = inf;
  }
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  dec.add(hq);
  dec.add(hc);
  dec.module(hc).set_max_influences(1);
  dec.module(hc).set_reduce_input(false);
  ASSERT_TRUE(dec.initialize());
  EXPECT_EQ(dec.decimate_to_faces(0, mesh.n_faces() / 2), 0u);
}

TEST(ModWeightCap, CapAtStorageCapacityIsTheSameAsNoCapModule) {
  Mesh a = omsk_test::load_character("X/Testwuson.X", 4);
  Mesh b = a;
  omsk_test::Modules with_cap, without_cap;
  with_cap.max_influences = Influences::kCapacity;
  without_cap.cap = false;
  omsk_test::decimate(a, 0.3, with_cap);
  omsk_test::decimate(b, 0.3, without_cap);
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  const auto h = influences_handle(a);
  for (auto vh : a.vertices()) {
    EXPECT_EQ(a.point(vh), b.point(vh));
    EXPECT_TRUE(a.property(h, vh) == b.property(h, vh));
  }
}

TEST(ModWeightCap, InvariantsAfterDecimatingARealCharacterToTenPercent) {
  for (CapStrategy strategy : {CapStrategy::Greedy, CapStrategy::TopN}) {
    Mesh mesh = omsk_test::load_character("X/Testwuson.X", 8);
    OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
    ModSkinnedQuadricT<Mesh>::Handle hq;
    ModWeightCapT<Mesh>::Handle hc;
    ModSkinnedFoldOverT<Mesh>::Handle hf;
    dec.add(hq);
    dec.add(hc);
    dec.add(hf);
    dec.module(hc).set_max_influences(2);
    dec.module(hc).set_strategy(strategy);
    ASSERT_TRUE(dec.initialize());
    const size_t before = mesh.n_faces();
    dec.decimate_to_faces(0, before / 10);
    mesh.garbage_collection();
    EXPECT_LE(mesh.n_faces(), before / 8);
    omsk_test::expect_valid_skin(mesh, 2);
  }
}
