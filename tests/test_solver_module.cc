// SolverModuleT: modules own their settings; the shared solver's are what the attached modules ask.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/Baselines/ModRestPoseQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <cmath>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(SolverModule, SettingsAreGatheredFromTheAttachedModules) {
  Mesh mesh = make_bending_cylinder(8, 16);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  dec.add(hq);
  dec.add(hc);
  dec.add(hf);
  dec.module(hc).set_max_influences(2);
  dec.module(hc).set_strategy(CapStrategy::Greedy);
  dec.module(hf).set_max_angle(60.0);
  dec.module(hq).set_max_iterations(3);
  dec.module(hq).set_tolerance(0.05);
  const SolverSettings& s = dec.module(hq).solver().settings();
  EXPECT_TRUE(s.placement);
  EXPECT_EQ(s.max_influences, 2);
  EXPECT_EQ(s.strategy, CapStrategy::Greedy);
  EXPECT_EQ(s.max_iterations, 3);
  EXPECT_EQ(s.tolerance, 0.05);
  EXPECT_TRUE(s.fold_check);
  EXPECT_NEAR(s.fold_cos, std::cos(M_PI / 3), 1e-12);
  EXPECT_EQ(&dec.module(hq).solver(), &dec.module(hc).solver()) << "one solver per mesh";
}

TEST(SolverModule, RemovingAModuleDropsOnlyItsOwnSettings) {
  Mesh mesh = make_bending_cylinder(8, 16);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  dec.add(hc);  // the cap module creates the shared solver
  dec.add(hq);
  dec.add(hf);
  dec.module(hc).set_max_influences(2);
  CollapseSolverT<Mesh>& solver = dec.module(hq).solver();
  dec.remove(hf);
  EXPECT_FALSE(solver.settings().fold_check);
  EXPECT_EQ(solver.settings().max_influences, 2);
  EXPECT_TRUE(solver.settings().placement);
  dec.remove(hc);  // the module that created the solver leaves; the solver stays for the others
  EXPECT_EQ(solver.settings().max_influences, Influences::kCapacity);
  EXPECT_TRUE(solver.settings().placement);
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> hs;
  EXPECT_TRUE(mesh.get_property_handle(hs, kSolverProperty));
  ASSERT_TRUE(dec.initialize());
  EXPECT_GT(dec.decimate_to_faces(0, mesh.n_faces() / 2), 0u);
  dec.remove(hq);
  EXPECT_FALSE(mesh.get_property_handle(hs, kSolverProperty)) << "the last module out removes the solver";
}

TEST(SolverModule, ARestSpaceModuleReplacesTheSkinnedQuadricAsTheEdgeModel) {
  // The rest-pose quadric ignores the example poses; the skinned quadric does not. Solve every edge of
  // the bending cylinder with and without its poses: the rest-pose module's answers must not change.
  using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;
  auto answers = [](bool with_poses, bool rest) {
    Mesh mesh = make_bending_cylinder(8, 16);
    if (!with_poses) use_bind_pose_only(mesh);
    OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
    ModRestPoseQuadricT<Mesh>::Handle hr;
    ModSkinnedQuadricT<Mesh>::Handle hq;
    std::vector<double> out;
    if (rest) {
      dec.add(hr);
      EXPECT_TRUE(dec.initialize());
      for (auto he : mesh.halfedges()) out.push_back(dec.module(hr).solver().solve(CI(mesh, he)).error);
    } else {
      dec.add(hq);
      EXPECT_TRUE(dec.initialize());
      for (auto he : mesh.halfedges()) out.push_back(dec.module(hq).solver().solve(CI(mesh, he)).error);
    }
    return out;
  };
  EXPECT_EQ(answers(true, true), answers(false, true));
  EXPECT_NE(answers(true, false), answers(false, false));
}

TEST(SolverModule, SolvingEveryEdgeAheadOnThreadsChangesNothingUnderDecimaterT) {
  using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
  const Mesh original = make_bending_cylinder(16, 24);
  Mesh meshes[2] = {original, original};
  for (int t = 0; t < 2; ++t) {
    Decimater dec(meshes[t]);
    omsk_test::SkinnedModules<Decimater> m(dec);
    dec.module(m.quadric).solver().set_threads(t == 0 ? 1 : 3);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, original.n_faces() / 5);
    // Every edge was solved once ahead; the decimation itself only re-solves what its collapses changed.
    EXPECT_GE(dec.module(m.quadric).solver().stats().solves, original.n_edges());
    dec.module(m.fold).release_deferred();
    meshes[t].garbage_collection();
  }
  omsk_test::expect_same_mesh(meshes[0], meshes[1]);
}
