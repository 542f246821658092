// ModJointGuardT: Savoye & Meyer's eta rule marks exactly the vertices it should, and those never disappear.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModJointGuardT.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// Every vertex rigid on joint 0 but three: v0 {0: .5, 1: .5}, v1 {1: 1}, v2 {0: .2, 1: .8}. Then
// eta(0) = (n - 3 + .5 + .2) / (n - 1) < 1 and eta(1) = (.5 + 1 + .8) / 3 = .767.
Mesh known_skin() {
  Mesh mesh = make_bending_cylinder(8, 8);
  const auto h = influences_handle(mesh);
  for (auto vh : mesh.vertices()) {
    Influences w;
    w.push(0, 1.0);
    mesh.property(h, vh) = w;
  }
  Influences a, b, c;
  a.push(0, 0.5), a.push(1, 0.5);
  b.push(1, 1.0);
  c.push(1, 0.8), c.push(0, 0.2);
  mesh.property(h, Mesh::VertexHandle(0)) = a;
  mesh.property(h, Mesh::VertexHandle(1)) = b;
  mesh.property(h, Mesh::VertexHandle(2)) = c;
  return mesh;
}

}  // namespace

TEST(ModJointGuard, MarksExactlyTheVerticesTheFormulaMarks) {
  Mesh mesh = known_skin();
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  ModJointGuardT<Mesh>::Handle hg;
  dec.add(hq);
  dec.add(hg);
  ASSERT_TRUE(dec.initialize());
  auto& guard = dec.module(hg);
  // tau = 1: rigid vertices (1.0 >= eta(0)), v1 (1.0 >= .767) and v2 (.8 >= .767) are guarded; v0 is not.
  EXPECT_TRUE(guard.eligible(Mesh::VertexHandle(0)));
  EXPECT_FALSE(guard.eligible(Mesh::VertexHandle(1)));
  EXPECT_FALSE(guard.eligible(Mesh::VertexHandle(2)));
  EXPECT_FALSE(guard.eligible(Mesh::VertexHandle(3)));
  // tau = 1.5: 1.5 eta(0) > 1 and 1.5 eta(1) = 1.15 > 1: nothing is guarded.
  guard.set_tau(1.5);
  guard.initialize();
  for (auto vh : mesh.vertices()) EXPECT_TRUE(guard.eligible(vh)) << vh.idx();
}

template <typename Decimater>
void guarded_vertices_survive() {
  Mesh mesh = make_bending_cylinder(16, 32);  // two bones blending at the knee
  Decimater dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  ModJointGuardT<Mesh>::Handle hg;
  dec.add(hq);
  dec.add(hg);
  ASSERT_TRUE(dec.initialize());
  std::vector<Mesh::VertexHandle> guarded;
  for (auto vh : mesh.vertices())
    if (!dec.module(hg).eligible(vh)) guarded.push_back(vh);
  ASSERT_GT(guarded.size(), 0u);
  ASSERT_LT(guarded.size(), mesh.n_vertices());
  const size_t n = dec.decimate(0);  // as far as it goes
  EXPECT_GT(n, 0u);
  for (auto vh : guarded) EXPECT_FALSE(mesh.status(vh).deleted()) << "guarded vertex " << vh.idx() << " removed";
}

TEST(ModJointGuard, GuardedVerticesSurviveUnderBothDrivers) {
  guarded_vertices_survive<OpenMesh::Decimater::DecimaterT<Mesh>>();
  guarded_vertices_survive<LazyDecimaterT<Mesh>>();
}
