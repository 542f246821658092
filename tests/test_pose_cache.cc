// Posed positions and per-pose quadrics per vertex (Solver/PoseCacheT.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/LoopSubdivision.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/PoseCacheT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(PoseCache, PosedPositionsAreTheSkinnedOnesAndEachPoseHasItsQuadrics) {
  Mesh mesh = make_bending_cylinder(8, 8);
  ASSERT_GE(example_poses(mesh).size(), 2u);
  PoseCacheT<Mesh> cache(mesh);
  cache.build();
  ASSERT_EQ(cache.n_poses(), int(example_poses(mesh).size()));
  const auto h = influences_handle(mesh);
  for (int j = 0; j < cache.n_poses(); ++j) {
    const auto posed = skin_positions(mesh, example_poses(mesh)[j]);
    for (auto vh : mesh.vertices()) {
      EXPECT_LT((cache.posed(vh, j) - posed[vh.idx()]).norm(), 1e-12);
      // A vertex lies on the planes of its own faces in every pose: its quadric is ~0 there.
      EXPECT_NEAR(cache.quadric(vh, j)(cache.posed(vh, j)), 0.0, 1e-9);
      EXPECT_EQ(cache.posed_point(to_eigen(mesh.point(vh)), mesh.property(h, vh), j), cache.posed(vh, j));
      // Stored in floats for the fold-over check: within float rounding of the model's size.
      EXPECT_LT((cache.posed_stored(vh.idx(), j) - posed[vh.idx()]).norm(), 1e-6);
    }
  }
}

TEST(PoseCache, AMeshWithoutExamplePosesIsRefusedWithWhatToDo) {
  Mesh mesh = make_bending_cylinder(8, 8);
  example_poses(mesh).clear();
  PoseCacheT<Mesh> cache(mesh);
  try {
    cache.build();
    FAIL() << "a mesh without example poses was decimated in some pose nobody asked for";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no example poses"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("use_bind_pose_only"), std::string::npos) << e.what();
  }
}

TEST(PoseCache, TheBindPoseAloneWhenAskedFor) {
  Mesh mesh = make_bending_cylinder(8, 8);
  use_bind_pose_only(mesh);
  PoseCacheT<Mesh> cache(mesh);
  cache.build();
  ASSERT_EQ(cache.n_poses(), 1);
  for (auto vh : mesh.vertices()) EXPECT_LT((cache.posed(vh, 0) - to_eigen(mesh.point(vh))).norm(), 1e-12);
}

TEST(PoseCache, UpdateFollowsAMovedVertexAndMergeSumsQuadrics) {
  Mesh mesh = make_bending_cylinder(8, 8);
  PoseCacheT<Mesh> cache(mesh);
  cache.build();
  const auto a = Mesh::VertexHandle(3), b = Mesh::VertexHandle(4);
  const Eigen::Vector3d x(0.3, -0.2, 0.5);
  std::vector<double> before;
  for (int j = 0; j < cache.n_poses(); ++j) before.push_back(cache.quadric(a, j)(x) + cache.quadric(b, j)(x));
  cache.merge_quadrics(a, b);
  // Stored in floats: the sum to float precision.
  for (int j = 0; j < cache.n_poses(); ++j) EXPECT_NEAR(cache.quadric(b, j)(x), before[j], 1e-6 * before[j]);
  mesh.set_point(b, mesh.point(b) + Mesh::Point(0, 0, 1));
  cache.update(b);
  const auto h = influences_handle(mesh);
  for (int j = 0; j < cache.n_poses(); ++j) {
    const Eigen::Vector3d want = skin_point(to_eigen(mesh.point(b)), mesh.property(h, b), cache.pose(j));
    EXPECT_LT((cache.posed(b, j) - want).norm(), 1e-12);
    EXPECT_LT((cache.posed_stored(b.idx(), j) - want).norm(), 1e-6);
    // The quadric is stored about the posed position, and moves with it: the same function of x.
    EXPECT_NEAR(cache.quadric(b, j)(x), before[j], 1e-6 * before[j]);
  }
}

TEST(PoseCache, QuadricsKeepTheirPrecisionFarFromTheOrigin) {
  // The same surface hundreds of model sizes away: about the origin, a float quadric's c grows with the
  // squared distance, and its rounding swamps the errors it must tell apart (checked: this test fails so).
  Mesh near = make_bending_cylinder(8, 8), far = near;
  use_bind_pose_only(near);
  use_bind_pose_only(far);
  const Mesh::Point shift(300, -200, 400);
  for (auto vh : far.vertices()) far.set_point(vh, far.point(vh) + shift);
  PoseCacheT<Mesh> a(near), b(far);
  a.build();
  b.build();
  const Eigen::Vector3d off(0.01, -0.02, 0.015), t = to_eigen(shift);
  for (auto vh : near.vertices()) {
    const Eigen::Vector3d x = a.posed(vh, 0) + off;
    const double want = a.quadric(vh, 0)(x);
    ASSERT_GT(want, 0.0);
    EXPECT_NEAR(b.quadric(vh, 0)(x + t), want, 1e-4 * want) << "vertex " << vh.idx();
  }
}

TEST(PoseCache, PositionsKeptInDoublesAreTheComputedOnesAndFollowUpdate) {
  // The deviation bound asks for them: read from the kept array, they must be what posed() computes.
  Mesh mesh = make_bending_cylinder(8, 8);
  PoseCacheT<Mesh> kept(mesh), computed(mesh);
  kept.set_keep_exact(true);
  kept.build();
  computed.build();
  const auto b = Mesh::VertexHandle(4);
  mesh.set_point(b, mesh.point(b) + Mesh::Point(0.25, 0, 0));
  kept.update(b);
  for (auto vh : mesh.vertices())
    for (int j = 0; j < kept.n_poses(); ++j) EXPECT_EQ(kept.posed(vh, j), computed.posed(vh, j));
}

TEST(PoseCache, TheTablesDoNotDependOnTheThreadCount) {
  // Testwuson: open borders, folds and seams all get planes; 9 poses shared out unevenly among threads.
  // Subdivided twice (15k vertices): smaller meshes are posed on fewer threads.
  Mesh mesh = loop_subdivide(loop_subdivide(omsk_test::load_character("X/Testwuson.X", 8)));
  ASSERT_GT(mesh.n_vertices(), 3u * 4096u);
  PoseCacheT<Mesh> one(mesh), three(mesh);
  one.set_keep_exact(true);
  three.set_keep_exact(true);
  one.build(1);
  three.build(3);
  ASSERT_EQ(one.n_poses(), three.n_poses());
  for (auto vh : mesh.vertices())
    for (int j = 0; j < one.n_poses(); ++j) {
      ASSERT_EQ(one.posed(vh, j), three.posed(vh, j));
      ASSERT_EQ(one.quadric(vh, j).A(), three.quadric(vh, j).A()) << "vertex " << vh.idx() << " pose " << j;
      ASSERT_EQ(one.quadric(vh, j).b(), three.quadric(vh, j).b());
      ASSERT_EQ(one.quadric(vh, j).c(), three.quadric(vh, j).c());
    }
}
