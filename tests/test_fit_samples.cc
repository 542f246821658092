// The original's samples of the final fit and the edge flips: vertices then centroids, strided to a budget.
#include "helpers.hh"

#include <OpenMeshSkinned/Solver/FitSamples.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(FitSamples, TrianglesFollowTheFacesCorners) {
  const Mesh mesh = omsk_test::grid_with_uv_seam();
  const auto triangles = mesh_triangles(mesh);
  ASSERT_EQ(triangles.size(), mesh.n_faces());
  for (auto fh : mesh.faces()) {
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) EXPECT_EQ(triangles[fh.idx()][k++], vh.idx());
  }
}

TEST(FitSamples, AllPointsWithinTheBudgetAndEveryOtherBeyondIt) {
  const Mesh mesh = omsk_test::grid_with_uv_seam();  // 9 vertices, 8 faces
  std::vector<size_t> all(17);
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  EXPECT_EQ(strided_samples(mesh, 8, 100), all);
  EXPECT_EQ(strided_samples(mesh, 8, 9), (std::vector<size_t>{0, 2, 4, 6, 8, 10, 12, 14, 16}));
}

TEST(FitSamples, SkipsDeletedVertices) {
  Mesh mesh = omsk_test::grid_with_uv_seam();
  mesh.request_vertex_status();
  mesh.status(Mesh::VertexHandle(4)).set_deleted(true);
  const auto s = strided_samples(mesh, 8, 100);
  EXPECT_EQ(std::count(s.begin(), s.end(), size_t(4)), 0);
  EXPECT_EQ(s.size(), 16u);
}

TEST(FitSamples, AVertexIsItselfAndATriangleItsCentroid) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}};
  const std::vector<std::array<int, 3>> triangles = {{0, 1, 2}};
  EXPECT_EQ(sample_point(points, triangles, 3, 1), Eigen::Vector3d(3, 0, 0));
  EXPECT_TRUE(sample_point(points, triangles, 3, 3).isApprox(Eigen::Vector3d(1, 1, 0)));
}
