// NonManifold: a vertex where two face fans meet is split so that both fans stay, with their corners.
#include <OpenMeshSkinned/Mesh/NonManifold.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

TEST(NonManifold, BowtieVertexGetsOneCopyPerExtraFan) {
  SkinnedMesh mesh;
  request_skinned_attributes(mesh);
  const auto h_inf = add_skin(mesh);
  const auto h_fmat = face_material_handle(mesh);
  // Two triangles touching only at the centre vertex c.
  const auto c = mesh.add_vertex({0, 0, 0});
  const auto a0 = mesh.add_vertex({1, 0, 0}), a1 = mesh.add_vertex({1, 1, 0});
  const auto b0 = mesh.add_vertex({-1, 0, 0}), b1 = mesh.add_vertex({-1, -1, 0});
  for (auto vh : mesh.vertices()) mesh.property(h_inf, vh) = Influences::rigid(vh.idx() % 2);
  const auto f0 = mesh.add_face(c, a0, a1), f1 = mesh.add_face(c, b0, b1);
  ASSERT_TRUE(f0.is_valid() && f1.is_valid());
  mesh.property(h_fmat, f0) = 3;
  mesh.property(h_fmat, f1) = 7;
  clear_corner_attributes(mesh);
  for (auto heh : mesh.fh_range(f1)) mesh.set_texcoord2D(heh, {0.25f, 0.75f});
  ASSERT_FALSE(mesh.is_manifold(c));

  EXPECT_EQ(split_nonmanifold_vertices(mesh, h_fmat), 1u);
  mesh.garbage_collection();
  EXPECT_EQ(mesh.n_faces(), 2u);
  EXPECT_EQ(mesh.n_vertices(), 6u);
  for (auto vh : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(vh));
  int mats = 0;
  for (auto fh : mesh.faces()) {
    mats += mesh.property(h_fmat, fh);
    if (mesh.property(h_fmat, fh) != 7) continue;
    for (auto heh : mesh.fh_range(fh)) {
      EXPECT_EQ(mesh.texcoord2D(heh), SkinnedMesh::TexCoord2D(0.25f, 0.75f));
    }
  }
  EXPECT_EQ(mats, 10);
  // The copy carries the centre's position and skin.
  int at_centre = 0;
  for (auto vh : mesh.vertices())
    if (mesh.point(vh) == SkinnedMesh::Point(0, 0, 0)) {
      ++at_centre;
      EXPECT_EQ(mesh.property(h_inf, vh), Influences::rigid(0));
    }
  EXPECT_EQ(at_centre, 2);
}
