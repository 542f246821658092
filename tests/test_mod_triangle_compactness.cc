// ModTriangleCompactnessT: the compactness measure, and the least compact triangle goes first, its vertices
// merged at its barycentre.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/Baselines/ModTriangleCompactnessT.hh>
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using Compact = ModTriangleCompactnessT<Mesh>;

TEST(ModTriangleCompactness, OneForEquilateralLessForOthersZeroForDegenerate) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0);
  EXPECT_NEAR(Compact::compactness(a, b, Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0)), 1.0, 1e-12);
  // Right isosceles: 4 sqrt(3) (1/2) / (1 + 1 + 2) = sqrt(3) / 2.
  EXPECT_NEAR(Compact::compactness(a, b, Eigen::Vector3d(0, 1, 0)), std::sqrt(3.0) / 2, 1e-12);
  EXPECT_EQ(Compact::compactness(a, b, Eigen::Vector3d(2, 0, 0)), 0.0);
  EXPECT_EQ(Compact::compactness(a, a, a), 0.0);
}

template <typename Decimater>
void least_compact_goes_first() {
  Mesh mesh = make_bending_cylinder(12, 12);
  // A sliver: one vertex pushed most of the way towards its neighbour along the ring.
  const Mesh::VertexHandle v(40), w(41);
  mesh.set_point(v, mesh.point(v) + 0.9f * (mesh.point(w) - mesh.point(v)));
  Mesh::FaceHandle worst;
  double c_min = 2.0;
  auto corners = [&](Mesh::FaceHandle f) {
    std::vector<Eigen::Vector3d> p;
    for (auto x : mesh.fv_range(f)) p.push_back(to_eigen(mesh.point(x)));
    return p;
  };
  for (auto f : mesh.faces()) {
    const auto p = corners(f);
    const double c = Compact::compactness(p[0], p[1], p[2]);
    if (c < c_min) c_min = c, worst = f;
  }
  ASSERT_LT(c_min, 0.3);
  const auto p = corners(worst);
  const Eigen::Vector3d barycentre = (p[0] + p[1] + p[2]) / 3.0;
  std::vector<Mesh::VertexHandle> fv;
  for (auto x : mesh.fv_range(worst)) fv.push_back(x);

  Decimater dec(mesh);
  typename Compact::Handle hc;
  dec.add(hc);
  ASSERT_TRUE(dec.initialize());
  ASSERT_EQ(dec.decimate(1), 1u);
  EXPECT_TRUE(mesh.status(worst).deleted()) << "the least compact triangle was not the first to go";
  int at_barycentre = 0, deleted = 0;
  for (auto x : fv) {
    deleted += mesh.status(x).deleted();
    at_barycentre += !mesh.status(x).deleted() && (to_eigen(mesh.point(x)) - barycentre).norm() < 1e-5;
  }
  EXPECT_EQ(deleted, 1);
  EXPECT_EQ(at_barycentre, 1);
}

TEST(ModTriangleCompactness, TheLeastCompactTriangleGoesFirstToItsBarycentre) {
  least_compact_goes_first<OpenMesh::Decimater::DecimaterT<Mesh>>();
  least_compact_goes_first<LazyDecimaterT<Mesh>>();
}
