// What a collapse does to the surviving vertex (Solver/CollapseApplierT.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/CollapseApplierT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

struct Parts {
  Parts(Mesh& mesh, int cap) : poses(mesh), answers(mesh, poses), applier(mesh, poses, answers) {
    poses.build();
    SolverSettings s;
    s.placement = true;
    s.max_influences = cap;
    answers.set_settings(s);
    answers.prepare();
    applier.prepare();
  }
  PoseCacheT<Mesh> poses;
  EdgeAnswersT<Mesh> answers;
  CollapseApplierT<Mesh> applier;
};

Mesh::HalfedgeHandle collapsible(Mesh& mesh, int from) {
  for (int i = from; i < int(mesh.n_halfedges()); ++i)
    if (mesh.is_collapse_ok(Mesh::HalfedgeHandle(i))) return Mesh::HalfedgeHandle(i);
  return Mesh::HalfedgeHandle();
}

}  // namespace

TEST(CollapseApplier, ThePlacedVertexTakesItsPlaceAndSkinAndIsPosedAndItsQuadricsSummed) {
  Mesh mesh = make_bending_cylinder(12, 16);
  Parts p(mesh, 2);
  const auto heh = collapsible(mesh, 100);
  ASSERT_TRUE(heh.is_valid());
  const CI ci(mesh, heh);
  const CollapseResult r = p.answers.solve(ci);
  ASSERT_TRUE(r.valid);
  std::vector<PoseQuadric> sum;
  for (int j = 0; j < p.poses.n_poses(); ++j) {
    PoseQuadric q = p.poses.quadric(ci.v0, j);
    q += p.poses.quadric(ci.v1, j);
    sum.push_back(q);
  }
  p.applier.record(ci);
  mesh.collapse(heh);
  p.applier.apply(ci, &r);
  EXPECT_EQ(to_eigen(mesh.point(ci.v1)), r.position);
  EXPECT_EQ(mesh.property(influences_handle(mesh), ci.v1).size(), r.weights.size());
  for (int j = 0; j < p.poses.n_poses(); ++j) {
    EXPECT_LT((p.poses.posed(ci.v1, j) - skin_point(r.position, r.weights, p.poses.pose(j))).norm(), 1e-12);
    const Eigen::Vector3d x(0.1, 0.2, 0.3);
    EXPECT_NEAR(p.poses.quadric(ci.v1, j)(x), sum[j](x), 1e-9 * (1.0 + std::abs(sum[j](x))));
  }
  for (auto fh : mesh.vf_range(ci.v1))
    EXPECT_LT((mesh.normal(fh) - mesh.calc_face_normal(fh)).norm(), 1e-12) << "its faces' normals follow it";
}

TEST(CollapseApplier, AVertexThatStaysKeepsItsPlaceAndASkinOverTheCapIsReducedByTheSolve) {
  Mesh mesh = omsk_test::many_influence_tube(8, 24);
  Parts p(mesh, 2);
  const auto h = influences_handle(mesh);
  Mesh::HalfedgeHandle heh;
  for (auto cand : mesh.halfedges())
    if (mesh.is_collapse_ok(cand) && mesh.property(h, mesh.to_vertex_handle(cand)).size() > 2) {
      heh = cand;
      break;
    }
  ASSERT_TRUE(heh.is_valid()) << "the tube has vertices with more than two bones";
  const CI ci(mesh, heh);
  const auto before = mesh.point(ci.v1);
  p.applier.record(ci);
  mesh.collapse(heh);
  p.applier.apply(ci, nullptr);
  EXPECT_EQ(mesh.point(ci.v1), before);
  EXPECT_LE(mesh.property(h, ci.v1).size(), 2);
  EXPECT_NEAR(mesh.property(h, ci.v1).sum(), 1.0, 1e-9);
  const size_t over = p.applier.reduce_input_influences();
  EXPECT_GT(over, 0u);
  for (auto vh : mesh.vertices()) EXPECT_LE(mesh.property(h, vh).size(), 2);
  EXPECT_EQ(p.applier.reduce_input_influences(), 0u) << "nothing left over the cap";
}
