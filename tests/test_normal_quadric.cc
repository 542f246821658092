// The rest-pose normal quadrics: a face's linear normal field, what a vertex pays for moving off where its
// faces' shading agrees, smoothing groups priced apart, and the solve that adds them to the geometry.
#include "helpers.hh"
#include "one_joint_edge.hh"

#include <OpenMeshSkinned/Solver/NormalQuadric.hh>
#include <OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh>

#include <functional>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// A flat grid in z = 0 of nx x ny vertices at unit spacing; each corner's stored normal is
// normal(vertex position, face centroid).
Mesh shaded_grid(int nx, int ny, const std::function<Eigen::Vector3d(Eigen::Vector2d, Eigen::Vector2d)>& normal) {
  Mesh mesh;
  request_skinned_attributes(mesh);
  std::vector<Mesh::VertexHandle> v;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) v.push_back(mesh.add_vertex(Mesh::Point(float(i), float(j), 0.f)));
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const auto a = v[j * nx + i], b = v[j * nx + i + 1], c = v[(j + 1) * nx + i + 1], d = v[(j + 1) * nx + i];
      mesh.add_face(a, b, c);
      mesh.add_face(a, c, d);
    }
  clear_corner_attributes(mesh);
  for (auto f : mesh.faces()) {
    const auto c = mesh.calc_face_centroid(f);
    for (auto h : mesh.fh_range(f)) {
      const auto p = mesh.point(mesh.to_vertex_handle(h));
      const Eigen::Vector3d n = normal({p[0], p[1]}, {c[0], c[1]}).normalized();
      mesh.set_normal(h, Mesh::Normal(float(n.x()), float(n.y()), float(n.z())));
    }
  }
  return mesh;
}

// The vertex (i, j) of a shaded_grid() nx wide.
int at(int nx, int i, int j) { return j * nx + i; }

}  // namespace

TEST(NormalQuadric, AFacesFieldInterpolatesItsCornerNormalsAndIsConstantAcrossTheFace) {
  const Eigen::Vector3d p0(0, 0, 0), p1(2, 0, 0), p2(0, 1, 0);
  const Eigen::Vector3d n0 = Eigen::Vector3d(0, 0, 1), n1 = Eigen::Vector3d(1, 0, 1).normalized(),
                        n2 = Eigen::Vector3d(0, 1, 2).normalized();
  Eigen::Matrix<double, 3, 4> B;
  ASSERT_TRUE(normal_field(p0, p1, p2, n0, n1, n2, B));
  auto N = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return B * x.homogeneous(); };
  EXPECT_LT((N(p0) - n0).norm(), 1e-12);
  EXPECT_LT((N(p1) - n1).norm(), 1e-12);
  EXPECT_LT((N(p2) - n2).norm(), 1e-12);
  EXPECT_LT((N(0.5 * (p1 + p2)) - 0.5 * (n1 + n2)).norm(), 1e-12);
  EXPECT_LT((N(p1 + Eigen::Vector3d(0, 0, 3)) - n1).norm(), 1e-12);  // off the face, along its normal
  // A sliver (height 10^-4 of its length) and a corner without a normal carry no field.
  EXPECT_FALSE(normal_field(p0, p1, Eigen::Vector3d(1, 1e-4, 0), n0, n1, n2, B));
  EXPECT_FALSE(normal_field(p0, p1, p2, n0, Eigen::Vector3d::Zero(), n2, B));
}

TEST(NormalQuadric, ALinearFieldCostsNothingAnywhere) {
  // Flat shading, and normals varying linearly over the grid (as on a sphere): every face's field is the
  // same one, so no placement spreads a normal where it was not.
  for (double tilt : {0.0, 0.05}) {
    const Mesh mesh =
        shaded_grid(4, 4, [&](Eigen::Vector2d p, Eigen::Vector2d) { return Eigen::Vector3d(tilt * p.x(), 0, 1); });
    std::vector<PoseQuadric> q;
    normal_quadrics(mesh, 1.0, q);
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(3, 0.5, 0), Eigen::Vector3d(-2, 7, 0)})
      EXPECT_NEAR(q[at(4, 1, 1)](x), 0.0, tilt == 0.0 ? 1e-12 : 1e-4) << tilt;
  }
}

TEST(NormalQuadric, ASmoothShadedEdgePricesWideningItsBandNotLengtheningIt) {
  // A smooth-shaded box edge seen on one side: the normals of the column x = 0 lean 45 degrees, the rest
  // are flat, so the shading bends within the band 0 < x < 1. Moving the vertex (1, 1) to x = 2 widens the
  // band over faces that showed flat shading; moving it along the edge does not.
  const Mesh mesh = shaded_grid(4, 3, [](Eigen::Vector2d p, Eigen::Vector2d) {
    return p.x() == 0.0 ? Eigen::Vector3d(-1, 0, 1) : Eigen::Vector3d(0, 0, 1);
  });
  std::vector<PoseQuadric> q;
  normal_quadrics(mesh, 1.0, q);
  const PoseQuadric& v = q[at(4, 1, 1)];
  EXPECT_NEAR(v(Eigen::Vector3d(1, 1, 0)), 0.0, 1e-9);
  EXPECT_NEAR(v(Eigen::Vector3d(1, 1.8, 0)), 0.0, 1e-9);
  EXPECT_GT(v(Eigen::Vector3d(2, 1, 0)), 0.1);
  // Beyond the band every face is flat: nothing to spread.
  EXPECT_NEAR(q[at(4, 2, 1)](Eigen::Vector3d(3, 1, 0)), 0.0, 1e-9);
}

TEST(NormalQuadric, SmoothingGroupsArePricedApart) {
  // A hard edge along x = 1: each face is flat-shaded with its own side's normal, so at a vertex on it the
  // corners come in two groups, each constant; taken as one group they disagree everywhere.
  const Mesh seam = shaded_grid(4, 3, [](Eigen::Vector2d, Eigen::Vector2d c) {
    return c.x() < 1.0 ? Eigen::Vector3d(-1, 0, 1) : Eigen::Vector3d(1, 0, 1);
  });
  std::vector<PoseQuadric> apart, together;
  normal_quadrics(seam, 1.0, apart);
  normal_quadrics(seam, 1.0, together, 1, -2.0);  // every corner one group
  const int v = at(4, 1, 1);
  const Eigen::Vector3d x(2, 1.5, 0);
  EXPECT_NEAR(apart[v](x), 0.0, 1e-12);
  EXPECT_GT(together[v](x), 0.1);
}

TEST(NormalQuadric, TheSolveAddsTheAttributeToTheGeometry) {
  // One joint, the plane z = 0 in its one pose: the geometry does not care where along the edge the vertex
  // goes, and the truncated solve keeps it at the midpoint. An attribute quadric x^2 pulls it to pa.
  EdgeProblem p = omsk_test::one_joint_edge(PoseQuadric::plane(Eigen::Vector3d::UnitZ(), 0.0, 1.0),
                                            Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0));
  WeightSolver weights;
  CollapseResult plain, priced;
  solve_collapse(p, SolveSettings{}, weights, plain);
  EXPECT_NEAR(plain.position.x(), 0.5, 1e-9);
  p.attribute = PoseQuadric::plane(Eigen::Vector3d::UnitX(), -0.25, 2.0);  // 2 (x - 0.25)^2
  solve_collapse(p, SolveSettings{}, weights, priced);
  EXPECT_NEAR(priced.position.x(), 0.25, 1e-9);
  EXPECT_NEAR(priced.error, 0.0, 1e-12);
  WeightSolver::Vector a(1);
  a[0] = 1.0;
  EXPECT_NEAR(skinned_energy(p, Eigen::Vector3d(1, 0, 0), a), 2 * 0.75 * 0.75, 1e-12);
}
