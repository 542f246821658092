// The shared solver's policy per driver (Solver/DriverPolicyT.hh, Solver/StaleVerdictPolicyT.hh): nothing to
// track under a driver that asks binary modules at pop time; DecimaterT's sweeps remembered and stale
// placements replaced under it.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/StaleVerdictPolicyT.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <algorithm>
#include <vector>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

struct Parts {
  explicit Parts(Mesh& mesh)
      : poses(mesh), answers(mesh, poses), fold(mesh, poses, answers), policy(mesh, answers, fold, clients, stats) {
    poses.build();
    SolverSettings s;
    s.placement = true;
    s.fold_check = true;
    s.fold_cos = 0.0;
    answers.set_settings(s);
    answers.prepare();
    policy.prepare();
  }
  std::vector<SolverClientT<Mesh>*> clients;
  CollapseSolverStats stats;
  PoseCacheT<Mesh> poses;
  EdgeAnswersT<Mesh> answers;
  FoldFallbackT<Mesh> fold;
  StaleVerdictPolicyT<Mesh> policy;
};

}  // namespace

TEST(DriverPolicy, APopTimeDriverLeavesNothingToTrack) {
  DriverPolicyT<Mesh> pop;
  Mesh mesh = make_bending_cylinder(8, 8);
  const CI ci(mesh, mesh.halfedge_handle(mesh.edge_handle(3), 0));
  pop.begin_pricing(ci);
  pop.note_legal(ci, 0.0);
  EXPECT_FALSE(pop.cannot_win(ci)) << "every collapse is priced: the binary modules are asked at pop time";
  CollapseResult r;
  r.valid = true;
  r.position = Eigen::Vector3d(1e9, 0, 0);
  pop.check_placement(ci, r);
  EXPECT_EQ(r.position.x(), 1e9) << "a verdict is never stale: the placement is not second-guessed";
}

TEST(DriverPolicy, TheSolverTakesThePolicyOfTheDriverItRunsUnder) {
  Mesh mesh = make_bending_cylinder(16, 16);
  {
    LazyDecimaterT<Mesh> lazy(mesh);
    ModSkinnedQuadricT<Mesh>::Handle hq;
    lazy.add(hq);
    ASSERT_TRUE(lazy.initialize());
    OpenMesh::VPropHandleT<bool> marks;
    EXPECT_FALSE(mesh.get_property_handle(marks, kDeferredProperty)) << "no deferral marks under the lazy driver";
    const CI ci(mesh, mesh.halfedge_handle(mesh.edge_handle(5), 0));
    lazy.module(hq).solver().note_legal_priority(ci, 0.0);
    EXPECT_FALSE(lazy.module(hq).solver().cannot_win(ci));
  }
  OpenMesh::Decimater::DecimaterT<Mesh> classic(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  classic.add(hf);
  classic.add(hq);
  ASSERT_TRUE(classic.initialize());
  OpenMesh::VPropHandleT<bool> marks;
  EXPECT_TRUE(mesh.get_property_handle(marks, kDeferredProperty)) << "DecimaterT's deferral marks its vertices";
  classic.decimate_to_faces(0, mesh.n_faces() / 4);
  classic.module(hf).release_deferred();
  for (auto vh : mesh.vertices()) EXPECT_FALSE(mesh.status(vh).locked());
}

TEST(DriverPolicy, UnderDecimaterTACollapsePricierThanItsSweepsBestCannotWin) {
  Mesh mesh = make_bending_cylinder(12, 12);
  Parts p(mesh);
  const auto v0 = Mesh::VertexHandle(40);
  auto priority = [&](Mesh::HalfedgeHandle h) { return p.answers.settings().priority(p.answers.solve(CI(mesh, h))); };
  std::vector<Mesh::HalfedgeHandle> hs;
  for (auto heh : mesh.voh_range(v0)) hs.push_back(heh);
  ASSERT_GE(hs.size(), 3u);
  std::sort(hs.begin(), hs.end(), [&](auto a, auto b) { return priority(a) < priority(b); });
  const std::vector<CI> out = {CI(mesh, hs.front()), CI(mesh, hs.back())};
  const double cheapest = priority(hs.front());
  ASSERT_LT(cheapest, priority(hs.back()));
  p.policy.begin_pricing(out.front());
  EXPECT_FALSE(p.policy.cannot_win(out.back())) << "nothing legal priced yet in this sweep";
  p.policy.note_legal(out.front(), cheapest);
  EXPECT_TRUE(p.policy.cannot_win(out.back()));
  // A new sweep (another v0) forgets it.
  p.policy.begin_pricing(CI(mesh, *mesh.voh_begin(Mesh::VertexHandle(41))));
  EXPECT_FALSE(p.policy.cannot_win(out.back()));
}

TEST(DriverPolicy, UnderDecimaterTAStalePlacementThatFoldsIsReplacedByOneThatDoesNot) {
  Mesh mesh = make_bending_cylinder(12, 12);
  Parts p(mesh);
  const CI ci(mesh, *mesh.voh_begin(Mesh::VertexHandle(40)));
  CollapseResult pending = p.answers.solve(ci);
  ASSERT_TRUE(pending.valid);
  // As if priced before a neighbour moved: a placement through the tube now folds.
  pending.position = Eigen::Vector3d(-pending.position.x(), pending.position.y(), -pending.position.z());
  ASSERT_TRUE(p.fold.flips(ci, pending.position, pending.weights, 0.0));
  p.policy.before_collapse(ci);
  p.policy.check_placement(ci, pending);
  ASSERT_TRUE(pending.valid);
  EXPECT_FALSE(p.fold.flips(ci, pending.position, pending.weights, 0.0));
  EXPECT_EQ(p.stats.placement_fallbacks, 1u);
  EXPECT_EQ(p.stats.forced_flips, 0u);
}
