// The fold-over test of one collapse (Collapse/FoldOver.hh), on hand-made triangles and a small fan.
#include "helpers.hh"

#include <OpenMeshSkinned/Collapse/FoldOver.hh>

#include <cmath>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {
const Eigen::Vector3d kA(1, 0, 0), kB(0, 1, 0), kC(0, 0, 0);
}

TEST(FoldOver, ARotationBelowTheLimitPassesAndOneAboveFails) {
  // Lifting the corner at the origin out of the plane z = 0 by h tilts the normal: the limit decides.
  for (double h : {0.1, 0.5, 2.0}) {
    const Eigen::Vector3d p(0, 0, h);
    const Eigen::Vector3d n0 = (kA - kC).cross(kB - kC).normalized(), n1 = (kA - p).cross(kB - p).normalized();
    const double angle = std::acos(n0.dot(n1));
    EXPECT_FALSE(face_folds(kC, kA, kB, p, std::cos(angle + 0.01))) << h;
    EXPECT_TRUE(face_folds(kC, kA, kB, p, std::cos(angle - 0.01))) << h;
  }
}

TEST(FoldOver, CrossingTheOppositeEdgeFlipsAndADegenerateResultFolds) {
  EXPECT_TRUE(face_folds(kC, kA, kB, Eigen::Vector3d(1, 1, 0), std::cos(M_PI * 0.99)));      // flipped: 180 degrees
  EXPECT_TRUE(face_folds(kC, kA, kB, Eigen::Vector3d(0.5, 0.5, 0), std::cos(M_PI * 0.99)));  // on the edge: no area
  EXPECT_FALSE(face_folds(kC, kA, kB, Eigen::Vector3d(0.2, 0.2, 0), std::cos(0.0)));         // moved in plane
}

TEST(FoldOver, AFaceThatHadNoAreaCannotTurn) {
  const Eigen::Vector3d c(0.5, 0.5, 0);  // on the edge AB: no normal before
  EXPECT_FALSE(face_folds(c, kA, kB, Eigen::Vector3d(0.2, 0.2, 0), 1.0));
}

TEST(FoldOver, SurvivingFacesAreTheRingWithoutTheTwoThatVanish) {
  // A hexagonal fan around v0, v1 one of its rim vertices with one more face outside: 6 faces around v0,
  // 3 around v1, 2 of them shared (they vanish); 4 + 1 survive.
  Mesh mesh;
  std::vector<Mesh::VertexHandle> rim;
  const auto v0 = mesh.add_vertex(Mesh::Point(0, 0, 0));
  for (int i = 0; i < 6; ++i)
    rim.push_back(mesh.add_vertex(Mesh::Point(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0)));
  for (int i = 0; i < 6; ++i) mesh.add_face(v0, rim[i], rim[(i + 1) % 6]);
  const auto outer = mesh.add_vertex(Mesh::Point(2, 0.5, 0));
  mesh.add_face(rim[0], outer, rim[1]);
  std::vector<RingFace> faces;
  surviving_faces(mesh, v0, rim[0], faces);
  EXPECT_EQ(faces.size(), 4u + 1u);  // v0's 6 minus the 2 with rim[0]; rim[0]'s 3 minus the same 2
  for (const RingFace& f : faces) {
    EXPECT_TRUE(f[0] == v0.idx() || f[0] == rim[0].idx());
    EXPECT_NE(f[1], f[0] == v0.idx() ? rim[0].idx() : v0.idx());
    EXPECT_NE(f[2], f[0] == v0.idx() ? rim[0].idx() : v0.idx());
  }
}

TEST(FoldOver, AnyPoseThatFoldsIsEnough) {
  const std::vector<RingFace> faces = {{0, 1, 2}};
  const std::vector<Eigen::Vector3d> pts = {kC, kA, kB};
  auto posed = [&](int v, int j) { return Eigen::Vector3d(pts[v] * (j + 1)); };
  // The merged vertex flips the face in pose 2 only.
  auto merged = [](int j) { return j == 2 ? Eigen::Vector3d(5, 5, 0) : Eigen::Vector3d(0.1, 0.1, 0); };
  EXPECT_FALSE(folds_in_any_pose(faces, 2, posed, merged, 0.5));
  EXPECT_TRUE(folds_in_any_pose(faces, 3, posed, merged, 0.5));
}
