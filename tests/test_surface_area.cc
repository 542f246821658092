// surface_area (Mesh/SurfaceArea.hh): what the tool's area floor is measured against.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/SurfaceArea.hh>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

using omsk_test::Mesh;

TEST(SurfaceArea, SumsTheLiveTrianglesAndLeavesDeletedOnesOut) {
  Mesh mesh;
  const auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({2, 0, 0}), c = mesh.add_vertex({2, 3, 0}),
             d = mesh.add_vertex({0, 3, 0}), e = mesh.add_vertex({0, 0, 4});
  mesh.add_face(a, b, c);
  mesh.add_face(a, c, d);
  const auto side = mesh.add_face(a, e, b);  // in the xz-plane: 2 x 4 / 2
  EXPECT_DOUBLE_EQ(OpenMeshSkinned::surface_area(mesh), 6.0 + 4.0);
  mesh.request_face_status();
  mesh.request_edge_status();
  mesh.request_vertex_status();
  mesh.delete_face(side, false);
  EXPECT_DOUBLE_EQ(OpenMeshSkinned::surface_area(mesh), 6.0);
  mesh.garbage_collection();
  EXPECT_DOUBLE_EQ(OpenMeshSkinned::surface_area(mesh), 6.0);
}

TEST(SurfaceArea, FansAPolygonFromItsFirstVertex) {
  OpenMesh::PolyMesh_ArrayKernelT<> poly;
  std::vector<OpenMesh::VertexHandle> ring;
  for (auto p :
       {OpenMesh::Vec3f(0, 0, 0), OpenMesh::Vec3f(2, 0, 0), OpenMesh::Vec3f(2, 3, 0), OpenMesh::Vec3f(0, 3, 0)})
    ring.push_back(poly.add_vertex(p));
  poly.add_face(ring);
  EXPECT_DOUBLE_EQ(OpenMeshSkinned::surface_area(poly), 6.0);
  EXPECT_DOUBLE_EQ(OpenMeshSkinned::surface_area(OpenMesh::PolyMesh_ArrayKernelT<>()), 0.0);
}
