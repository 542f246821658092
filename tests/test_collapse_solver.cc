#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/CollapseSolverT.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

// A flat grid in z = 0 over [0,1]^2, two joints, weight on joint 1 equal to x. Pose 0 is the bind pose;
// in pose 1 joint 1 moves by +d along z, so the posed surface is the plane z = d x. The merged vertex of
// any interior edge fits both poses exactly iff its weight on joint 1 equals its x.
Mesh two_joint_sheet(int n, double d) {
  Mesh mesh;
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  const auto h = add_skin(mesh);
  Joint j0, j1;
  j0.name = "j0";
  j1.name = "j1";
  j1.parent = 0;
  skeleton(mesh).joints = {j0, j1};
  std::vector<Mesh::VertexHandle> vh;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double x = double(k) / n, y = double(i) / n;
      auto v = mesh.add_vertex(Mesh::Point(x, y, 0));
      Influences inf;
      if (x < 1.0) inf.push(0, 1.0 - x);
      if (x > 0.0) inf.push(1, x);
      inf.sort();
      mesh.property(h, v) = inf;
      vh.push_back(v);
    }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      auto a = vh[i * (n + 1) + k], b = vh[i * (n + 1) + k + 1], c = vh[(i + 1) * (n + 1) + k],
           e = vh[(i + 1) * (n + 1) + k + 1];
      mesh.add_face(a, b, e);
      mesh.add_face(a, e, c);
    }
  clear_corner_attributes(mesh);  // OpenMesh leaves them uninitialised: a stray normal would be a hard edge
  Pose bent = Pose::identity(2);
  bent.joint[1](2, 3) = d;
  example_poses(mesh) = {Pose::identity(2), bent};
  return mesh;
}

Mesh::HalfedgeHandle interior_halfedge(const Mesh& mesh) {
  for (auto heh : mesh.halfedges()) {
    const auto a = mesh.point(mesh.from_vertex_handle(heh)), b = mesh.point(mesh.to_vertex_handle(heh));
    if (!mesh.is_boundary(mesh.edge_handle(heh)) && !mesh.is_boundary(mesh.from_vertex_handle(heh)) &&
        !mesh.is_boundary(mesh.to_vertex_handle(heh)) && a[0] != b[0] && a[0] > 0.2 && a[0] < 0.8)
      return heh;
  }
  return Mesh::HalfedgeHandle();
}

}  // namespace

TEST(CollapseSolver, TwoJointSheetFindsTheWeightThatFitsEveryPose) {
  Mesh mesh = two_joint_sheet(8, 0.5);
  CollapseSolverT<Mesh> solver(mesh);
  solver.prepare();
  const auto heh = interior_halfedge(mesh);
  ASSERT_TRUE(heh.is_valid());
  CI ci(mesh, heh);
  const CollapseResult& r = solver.solve(ci);
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.error, 0.0, 1e-12);
  EXPECT_NEAR(r.weights.weight_of(1), r.position.x(), 1e-6);
  EXPECT_NEAR(r.weights.sum(), 1.0, 1e-9);
  EXPECT_NEAR(r.position.z(), 0.0, 1e-9);
  // Plain averaging of the endpoints' weights is exact here too, but a position off the edge's midpoint
  // must pull the weight along: the solver's weight follows its own x, not the endpoints'.
}

TEST(CollapseSolver, SinglePoseOptimumIsTheStaticQuadricOptimum) {
  Mesh mesh = make_bending_cylinder(12, 12);
  example_poses(mesh) = {Pose::identity(skeleton(mesh).size())};
  CollapseSolverT<Mesh> solver(mesh);
  solver.prepare();
  int checked = 0;
  for (auto heh : mesh.halfedges()) {
    if (mesh.is_boundary(mesh.edge_handle(heh))) continue;
    CI ci(mesh, heh);
    const CollapseResult& r = solver.solve(ci);
    Eigen::Matrix4d Q = solver.quadric(ci.v0, 0).matrix() + solver.quadric(ci.v1, 0).matrix();
    const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
    // Well-conditioned only: the solver leaves nearly unconstrained directions at the midpoint.
    if (A.jacobiSvd().singularValues()(2) < 1e-2 * A.jacobiSvd().singularValues()(0)) continue;
    const Eigen::Vector3d opt = A.ldlt().solve(-Q.topRightCorner<3, 1>());
    EXPECT_LE((r.position - opt).norm(), 1e-8 * (1.0 + opt.norm()));
    if (++checked >= 50) break;
  }
  EXPECT_GT(checked, 10);
}

TEST(CollapseSolver, ConstraintsHoldForEveryEdgeOfARealCharacter) {
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 6);
  CollapseSolverT<Mesh> solver(mesh);
  SolverSettings settings;
  settings.max_influences = 3;
  solver.set_settings(settings);
  solver.prepare();
  for (auto heh : mesh.halfedges()) {
    CI ci(mesh, heh);
    const CollapseResult& r = solver.solve(ci);
    ASSERT_TRUE(r.valid);
    EXPECT_GE(r.error, 0.0);
    EXPECT_LE(r.weights.size(), 3);
    EXPECT_NEAR(r.weights.sum(), 1.0, 1e-9);
    for (const auto& jw : r.weights) EXPECT_GT(jw.weight, 0.0);
  }
  // Each edge was solved once; the second halfedge of every edge came from the cache.
  EXPECT_EQ(solver.stats().solves, mesh.n_edges());
  EXPECT_EQ(solver.stats().cache_hits, mesh.n_edges());
}

TEST(CollapseSolver, RaisingTheCapAfterPrepareGivesTheWiderAnswersAndCachesThem) {
  // The cache's slots are sized for the cap at prepare(); raised later, the slots are widened, and every
  // answer is the one a solver prepared with the higher cap gives.
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 6);
  SolverSettings narrow, wide;
  narrow.max_influences = 2;
  wide.max_influences = 6;
  CollapseSolverT<Mesh> solver(mesh), fresh(mesh);
  solver.set_settings(narrow);
  solver.prepare();
  for (auto heh : mesh.halfedges()) solver.solve(CI(mesh, heh));
  solver.set_settings(wide);
  fresh.set_settings(wide);
  fresh.prepare();
  const auto solves = solver.stats().solves, hits = solver.stats().cache_hits;
  int wider = 0;
  for (auto heh : mesh.halfedges()) {
    const CollapseResult r = solver.solve(CI(mesh, heh));
    const CollapseResult& f = fresh.solve(CI(mesh, heh));
    EXPECT_EQ(r.weights, f.weights);
    EXPECT_EQ(r.error, f.error);
    wider += r.weights.size() > 2;
  }
  EXPECT_GT(wider, 0);
  EXPECT_EQ(solver.stats().solves, solves + mesh.n_edges());
  EXPECT_EQ(solver.stats().cache_hits, hits + mesh.n_edges());
}

TEST(CollapseSolver, TheErrorAtAPlacementIsTheSolvesOwnAndAFallbackIsTheCheapestThatFoldsNothing) {
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 6);
  CollapseSolverT<Mesh> solver(mesh);
  SolverSettings settings;
  settings.placement = true;
  settings.fold_check = true;
  solver.set_settings(settings);
  solver.prepare();
  const double min_cos = std::cos(20.0 * M_PI / 180.0);
  const auto h = influences_handle(mesh);
  int folding = 0, chosen = 0;
  for (auto heh : mesh.halfedges()) {
    const CI ci(mesh, heh);
    if (!mesh.is_collapse_ok(heh)) continue;
    const CollapseResult solved = solver.solve(ci);
    ASSERT_TRUE(solved.valid);
    // The kernel sums the poses out in joint space; error_at poses the vertex pose by pose.
    EXPECT_NEAR(solver.error_at(ci, solved.position, solved.weights), solved.error, 1e-9 + 1e-6 * solved.error);
    if (!solver.flips(ci, solved.position, solved.weights, min_cos)) continue;
    ++folding;
    if (!solver.choose_fallback_placement(ci, min_cos)) {
      EXPECT_EQ(&solver.placement(ci), &solver.solve(ci)) << "nothing chosen: the solved answer stands";
      continue;
    }
    ++chosen;
    const CollapseResult r = solver.placement(ci);
    EXPECT_FALSE(solver.flips(ci, r.position, r.weights, min_cos));
    EXPECT_LE(r.weights.size(), settings.max_influences);
    EXPECT_NEAR(r.weights.sum(), 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(r.error, solver.error_at(ci, r.position, r.weights));
    EXPECT_GE(r.error, solved.error * (1.0 - 1e-6)) << "the solve's own placement is the cheapest";
    // No other placement of the five that folds nothing is cheaper.
    const Eigen::Vector3d p0 = to_eigen(mesh.point(ci.v0)), p1 = to_eigen(mesh.point(ci.v1));
    const std::pair<Eigen::Vector3d, Influences> others[] = {{p1, solved.weights},
                                                             {0.5 * (p0 + p1), solved.weights},
                                                             {p0, solved.weights},
                                                             {p1, mesh.property(h, ci.v1)},
                                                             {p0, mesh.property(h, ci.v0)}};
    for (const auto& [p, w] : others) {
      if (w.size() <= settings.max_influences && !solver.flips(ci, p, w, min_cos)) {
        EXPECT_LE(r.error, solver.error_at(ci, p, w) * (1.0 + 1e-12));
      }
    }
    // Chosen for this collapse only: pricing another forgets it.
    solver.begin_pricing(CI(mesh, mesh.opposite_halfedge_handle(heh)));
    EXPECT_EQ(&solver.placement(ci), &solver.solve(ci));
  }
  EXPECT_GT(folding, 10);
  EXPECT_GT(chosen, 0);
}

TEST(CollapseSolver, CacheIsInvalidatedWhenAnEndpointChanges) {
  Mesh mesh = two_joint_sheet(6, 0.5);
  CollapseSolverT<Mesh> solver(mesh);
  SolverSettings settings;
  settings.placement = true;
  solver.set_settings(settings);
  solver.prepare();
  const auto heh = interior_halfedge(mesh);
  CI ci(mesh, heh);
  solver.solve(ci);
  solver.solve(ci);
  EXPECT_EQ(solver.stats().solves, 1u);
  // Collapse a neighbouring edge into one endpoint: the cached answer must not be reused.
  Mesh::HalfedgeHandle other;
  for (auto h : mesh.voh_range(ci.v1))
    if (mesh.to_vertex_handle(h) != ci.v0 && mesh.is_collapse_ok(mesh.opposite_halfedge_handle(h))) {
      other = mesh.opposite_halfedge_handle(h);
      break;
    }
  ASSERT_TRUE(other.is_valid());
  CI co(mesh, other);
  solver.begin_collapse(co);
  mesh.collapse(other);
  solver.end_collapse(co);
  const auto solves = solver.stats().solves;
  const auto again = mesh.find_halfedge(ci.v0, ci.v1);
  ASSERT_TRUE(again.is_valid());
  CI cn(mesh, again);
  solver.solve(cn);
  EXPECT_EQ(solver.stats().solves, solves + 1);
  solver.solve(cn);
  EXPECT_EQ(solver.stats().solves, solves + 1);
}
