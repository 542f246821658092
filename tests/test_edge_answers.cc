// The shared solver's edge answers (Solver/EdgeAnswersT.hh): cached per edge until an endpoint changes,
// the same whether solved one by one or all ahead on threads, and a module's cost model in place of the kernel.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/EdgeAnswersT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

SolverSettings placing(int cap = 4) {
  SolverSettings s;
  s.placement = true;
  s.max_influences = cap;
  return s;
}

void expect_same_answer(const CollapseResult& a, const CollapseResult& b) {
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.area, b.area);
  ASSERT_EQ(a.weights.size(), b.weights.size());
  for (int k = 0; k < a.weights.size(); ++k) {
    EXPECT_EQ(a.weights[k].joint, b.weights[k].joint);
    EXPECT_EQ(a.weights[k].weight, b.weights[k].weight);
  }
}

// Places every merged vertex at the midpoint, and counts how often it was asked.
struct MidpointModel : EdgeModelT<Mesh> {
  explicit MidpointModel(const Mesh& m) : mesh(m) {}
  void solve_edge(Mesh::VertexHandle a, Mesh::VertexHandle b, CollapseResult& out) override {
    ++calls;
    out.position = 0.5 * (to_eigen(mesh.point(a)) + to_eigen(mesh.point(b)));
    out.weights = mesh.property(influences_handle(mesh), a);
    out.error = 1.0;
    out.valid = true;
  }
  const Mesh& mesh;
  int calls = 0;
};

}  // namespace

TEST(EdgeAnswers, AllEdgesSolvedAheadOnThreadsAreTheAnswersSolvedOneByOne) {
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 4);
  PoseCacheT<Mesh> poses(mesh);
  poses.build();
  EdgeAnswersT<Mesh> one(mesh, poses), ahead(mesh, poses);
  one.set_settings(placing());
  ahead.set_settings(placing());
  one.prepare();
  ahead.prepare();
  ahead.solve_all_edges(3);
  CollapseSolverStats before;
  ahead.add_counts(before);
  EXPECT_EQ(before.solves, mesh.n_edges());
  for (auto eh : mesh.edges()) {
    const CI ci(mesh, mesh.halfedge_handle(eh, 0));
    const CollapseResult a = one.solve(ci);
    expect_same_answer(a, ahead.solve(ci));
  }
  CollapseSolverStats after;
  ahead.add_counts(after);
  EXPECT_EQ(after.solves, mesh.n_edges()) << "every answer came from the cache";
  EXPECT_EQ(after.cache_hits, mesh.n_edges());
}

TEST(EdgeAnswers, AChangedEndpointOrANewCapIsSolvedAgain) {
  Mesh mesh = make_bending_cylinder(8, 12);
  PoseCacheT<Mesh> poses(mesh);
  poses.build();
  EdgeAnswersT<Mesh> answers(mesh, poses);
  answers.set_settings(placing(2));
  answers.prepare();
  const CI ci(mesh, mesh.halfedge_handle(mesh.edge_handle(40), 0));
  auto solves = [&] {
    CollapseSolverStats s;
    answers.add_counts(s);
    return s.solves;
  };
  answers.solve(ci);
  answers.solve(ci);
  EXPECT_EQ(solves(), 1u);
  answers.vertex_changed(ci.v1);
  answers.solve(ci);
  EXPECT_EQ(solves(), 2u);
  SolverSettings same = placing(2);
  same.fold_check = true;  // does not change an answer: the cache stays
  answers.set_settings(same);
  answers.solve(ci);
  EXPECT_EQ(solves(), 2u);
  answers.set_settings(placing(1));
  EXPECT_EQ(answers.solve(ci).weights.size(), 1);
  EXPECT_EQ(solves(), 3u);
}

TEST(EdgeAnswers, AModulesCostModelAnswersInsteadOfTheKernel) {
  Mesh mesh = make_bending_cylinder(8, 12);
  PoseCacheT<Mesh> poses(mesh);
  poses.build();
  EdgeAnswersT<Mesh> answers(mesh, poses);
  MidpointModel model(mesh);
  answers.set_settings(placing());
  answers.set_model(&model);
  answers.prepare();
  answers.solve_all_edges(2);
  EXPECT_EQ(model.calls, 0) << "a module's model need not be safe to call on threads: nothing solved ahead";
  const CI ci(mesh, mesh.halfedge_handle(mesh.edge_handle(7), 0));
  const CollapseResult r = answers.solve(ci);
  EXPECT_EQ(model.calls, 1);
  EXPECT_TRUE(r.position.isApprox(0.5 * (to_eigen(mesh.point(ci.v0)) + to_eigen(mesh.point(ci.v1)))));
  answers.solve(ci);
  EXPECT_EQ(model.calls, 1) << "its answers are cached as the kernel's are";
  EXPECT_EQ(answers.answer_capacity(), Influences::kCapacity);
}
