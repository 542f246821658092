// The fold check's placements (Solver/FoldFallbackT.hh): what folds, and the cheapest placement that does not.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/FoldFallbackT.hh>

#include <cmath>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

struct Parts {
  explicit Parts(Mesh& mesh) : poses(mesh), answers(mesh, poses), fold(mesh, poses, answers) {
    poses.build();
    SolverSettings s;
    s.placement = true;
    answers.set_settings(s);
    answers.prepare();
  }
  PoseCacheT<Mesh> poses;
  EdgeAnswersT<Mesh> answers;
  FoldFallbackT<Mesh> fold;
};

// An edge of the tube's middle ring, away from its open ends.
CI middle_edge(Mesh& mesh) {
  for (auto heh : mesh.halfedges())
    if (!mesh.is_boundary(mesh.from_vertex_handle(heh)) && !mesh.is_boundary(mesh.to_vertex_handle(heh)) &&
        mesh.is_collapse_ok(heh) && std::abs(mesh.point(mesh.from_vertex_handle(heh))[1] - 1.0) < 0.2)
      return CI(mesh, heh);
  ADD_FAILURE() << "no middle edge";
  return CI(mesh, Mesh::HalfedgeHandle(0));
}

}  // namespace

TEST(FoldFallback, TheSolvedPlacementOfASmoothEdgeFoldsNothingAndOneFarAcrossFolds) {
  Mesh mesh = make_bending_cylinder(16, 24);
  Parts p(mesh);
  const CI ci = middle_edge(mesh);
  const CollapseResult& r = p.answers.solve(ci);
  ASSERT_TRUE(r.valid);
  const double min_cos = std::cos(60.0 * M_PI / 180.0);
  EXPECT_FALSE(p.fold.flips(ci, r.position, r.weights, min_cos));
  // Through the tube to the other side: the faces around the merged vertex turn inside out.
  const Eigen::Vector3d across(-r.position.x(), r.position.y(), -r.position.z());
  EXPECT_TRUE(p.fold.flips(ci, across, r.weights, min_cos));
}

TEST(FoldFallback, AChosenPlacementIsTheCheapestOfTheFiveThatFoldsNothingAndStandsForItsCollapseOnly) {
  Mesh mesh = make_bending_cylinder(16, 24);
  Parts p(mesh);
  const CI ci = middle_edge(mesh);
  const CollapseResult solved = p.answers.solve(ci);
  // A limit no placement but a near-flat one meets: some of the five fold, the cheapest of the rest is taken.
  const double min_cos = 0.99999;
  bool any_ok = false;
  double best = 1e300;
  for (const auto& [pos, w] : p.fold.placements_to_try(ci, solved))
    if (!p.fold.flips(ci, pos, w, min_cos)) any_ok = true, best = std::min(best, p.fold.error_at(ci, pos, w));
  ASSERT_EQ(p.fold.choose(ci, min_cos), any_ok);
  if (any_ok) {
    EXPECT_TRUE(p.fold.chosen_for(ci));
    EXPECT_DOUBLE_EQ(p.fold.chosen().error, best);
    EXPECT_EQ(&p.fold.placement(ci), &p.fold.chosen());
    const CI other(mesh, mesh.opposite_halfedge_handle(ci.v0v1));
    EXPECT_FALSE(p.fold.chosen_for(other)) << "the choice is for one direction of one edge";
  }
  p.fold.forget();
  EXPECT_FALSE(p.fold.chosen_for(ci));
  Eigen::Vector3d rest;
  Influences w;
  p.fold.placement_of(ci, rest, w);
  EXPECT_EQ(rest, p.answers.solve(ci).position) << "forgotten: the solved placement again";
}

TEST(FoldFallback, TheErrorAtThePlacementIsTheSolvesOwn) {
  Mesh mesh = make_bending_cylinder(16, 24);
  Parts p(mesh);
  for (int e = 0; e < int(mesh.n_edges()); e += 17) {
    const CI ci(mesh, mesh.halfedge_handle(mesh.edge_handle(e), 0));
    const CollapseResult r = p.answers.solve(ci);
    if (!r.valid) continue;
    EXPECT_NEAR(p.fold.error_at(ci, r.position, r.weights), r.error, 1e-9 + 1e-6 * r.error);
  }
}
