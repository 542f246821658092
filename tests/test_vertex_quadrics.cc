// accumulate_quadrics: face planes, border planes, the planes of a sheet folded back on itself and those of a
// UV seam.
#include "helpers.hh"

#include <OpenMeshSkinned/Solver/VertexQuadrics.hh>

#include <mutex>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// Two triangles on the edge p0 = (0,0,0), p1 = (1,0,0): one towards t = (0,1,0) in the plane z = 0, the other
// towards u, given per configuration (configurations are the quadrics' "poses"). With \p seam the two faces
// belong to different UV charts.
struct Hinge {
  Mesh mesh;
  std::vector<Eigen::Vector3d> u;  // per configuration
  std::vector<PoseQuadric> q;      // vertex v, configuration j at v * n + j
  explicit Hinge(std::vector<Eigen::Vector3d> us, bool seam = false) : u(std::move(us)) {
    const auto p0 = mesh.add_vertex({0, 0, 0}), p1 = mesh.add_vertex({1, 0, 0});
    const auto t = mesh.add_vertex({0, 1, 0}), w = mesh.add_vertex({0, 0, 0});
    mesh.add_face(p0, p1, t);
    const auto f1 = mesh.add_face(p1, p0, w);
    clear_corner_attributes(mesh);
    if (seam)
      for (auto h : mesh.fh_range(f1)) mesh.set_texcoord2D(h, Mesh::TexCoord2D(0.5f, 0.5f));
    const int n = int(u.size());
    q.assign(4 * u.size(), PoseQuadric{});
    accumulate_quadrics(
        mesh, n,
        [&](Mesh::VertexHandle v, int j) -> Eigen::Vector3d {
          return v.idx() == 3 ? u[j] : Eigen::Vector3d(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
        },
        [&](Mesh::VertexHandle v, int j) -> PoseQuadric& { return q[v.idx() * n + j]; });
  }
};

}  // namespace

TEST(VertexQuadrics, ASheetFoldedBackOnItselfKeepsItsOutline) {
  // u = (0, 1, 0.01): the second triangle lies back on the first (normals opposite). Both face planes are
  // z = 0 (about): only the fold's own planes (y = 0, through the edge, across the sheet) price p0 sliding
  // into the sheet by 0.3, as much as a border would (weight: squared edge length, once per face).
  const Hinge folded({Eigen::Vector3d(0, 1, 0.01)});
  const Eigen::Vector3d inward(0, 0.3, 0);
  EXPECT_GT(folded.q[0](inward), 2 * 0.09 * 0.99);
  // Opened flat (u = (0, -1, 0)) the same slide costs only what the open borders charge.
  const Hinge flat({Eigen::Vector3d(0, -1, 0)});
  EXPECT_LT(flat.q[0](inward), 0.1);
  // Along the fold nothing changes: the fold's planes contain the edge.
  EXPECT_NEAR(folded.q[0](Eigen::Vector3d(0.3, 0, 0)) - flat.q[0](Eigen::Vector3d(0.3, 0, 0)), 0.0, 0.02);
}

TEST(VertexQuadrics, AFoldThatOnlyAPoseMakesIsNoFold) {
  // Flat in configuration 0, folded in configuration 1 (as the inside of a bent knee): no fold planes in
  // either, so the pose's crease does not pin the joint.
  const Hinge bent({Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 1, 0.01)});
  const Hinge folded({Eigen::Vector3d(0, 1, 0.01)});
  const Eigen::Vector3d inward(0, 0.3, 0);
  EXPECT_LT(bent.q[0 * 2 + 1](inward), 0.1);
  EXPECT_GT(folded.q[0](inward), 0.17);
}

TEST(VertexQuadrics, AUvSeamKeepsItsLineOnAFlatSheet) {
  // Flat (u = (0, -1, 0)), the two faces in different UV charts: sliding p0 across the seam by 0.3 costs
  // kSeamPlaneWeight of what a fold charges (a plane per face, weight: squared edge length), so the seam
  // stays where the texture is cut; along the seam the cost is that of the open borders alone.
  const Hinge seam({Eigen::Vector3d(0, -1, 0)}, true);
  const Hinge flat({Eigen::Vector3d(0, -1, 0)});
  const Eigen::Vector3d inward(0, 0.3, 0), along(0.3, 0, 0);
  EXPECT_NEAR(seam.q[0](inward) - flat.q[0](inward), kSeamPlaneWeight * 2 * 0.09, 1e-9);
  EXPECT_NEAR(seam.q[0](along), flat.q[0](along), 1e-12);
}

TEST(VertexQuadrics, OneConfigurationAtATimeSumsWhatAllAtOnceSum) {
  // A hinge folded in some configurations and not others: every kind of plane, on one and on two threads.
  Hinge all({Eigen::Vector3d(0, 1, 0.05), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.1, 1, -0.02)});
  const int n = int(all.u.size());
  auto pos = [&](Mesh::VertexHandle v, int j) -> Eigen::Vector3d {
    const auto& p = all.mesh.point(v);
    return v.idx() == 3 ? all.u[j] : Eigen::Vector3d(p[0], p[1], p[2]);
  };
  for (int threads : {1, 2}) {
    std::vector<int> seen(n, 0);
    std::mutex m;
    accumulate_quadrics_by_configuration(
        all.mesh, n, pos, [](auto) { return 1.0; },
        [&](int j, const std::vector<PoseQuadric>& sum) {
          std::lock_guard<std::mutex> lock(m);
          ++seen[j];
          ASSERT_EQ(sum.size(), all.mesh.n_vertices());
          for (auto v : all.mesh.vertices())
            for (int i = 0; i < 10; ++i) EXPECT_EQ(sum[v.idx()].q[i], all.q[v.idx() * n + j].q[i]) << j;
        },
        threads);
    EXPECT_EQ(seen, std::vector<int>(n, 1));
  }
}
