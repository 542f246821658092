// UV re-interpolation after a collapse (Decimater/UvTransferT.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/UvTransferT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

Mesh::HalfedgeHandle halfedge(const Mesh& mesh, Mesh::Point from, Mesh::Point to) {
  for (auto h : mesh.halfedges())
    if (mesh.point(mesh.from_vertex_handle(h)) == from && mesh.point(mesh.to_vertex_handle(h)) == to) return h;
  return Mesh::HalfedgeHandle();
}

}  // namespace

TEST(UvTransfer, AllZeroUvsAreNotBookkept) {
  Mesh mesh = omsk_test::grid_with_uv_seam();
  for (auto h : mesh.halfedges()) mesh.set_texcoord2D(h, Mesh::TexCoord2D(0, 0));
  UvTransferT<Mesh> uv(mesh);
  uv.prepare();
  EXPECT_FALSE(uv.active());
}

TEST(UvTransfer, BorderHalfedgesDoNotCount) {
  // A border halfedge has no face; whatever its UV holds, the mesh has no UVs to keep.
  Mesh mesh = omsk_test::grid_with_uv_seam();
  for (auto h : mesh.halfedges())
    mesh.set_texcoord2D(h, mesh.is_boundary(h) ? Mesh::TexCoord2D(3.5f, -1.0f) : Mesh::TexCoord2D(0, 0));
  UvTransferT<Mesh> uv(mesh);
  uv.prepare();
  EXPECT_FALSE(uv.active());
}

TEST(UvTransfer, AMovedVertexTakesTheUvOfWhereItLandsInItsOwnChart) {
  Mesh mesh = omsk_test::grid_with_uv_seam();
  UvTransferT<Mesh> uv(mesh);
  uv.prepare();
  ASSERT_TRUE(uv.active());
  // Collapse the left-column centre vertex (0,1) into the centre (1,1), then move the survivor to (0.5, 1).
  const auto h = halfedge(mesh, Mesh::Point(0, 1, 0), Mesh::Point(1, 1, 0));
  ASSERT_TRUE(h.is_valid());
  const auto v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  uv.record(v0, v1);
  mesh.collapse(h);
  mesh.set_point(v1, Mesh::Point(0.5, 1, 0));
  uv.apply(v1);
  int left = 0, right = 0;
  for (auto hi : mesh.vih_range(v1)) {
    if (mesh.is_boundary(hi)) continue;
    const auto t = mesh.texcoord2D(hi);
    if (t[0] < 5) {
      ++left;  // the left chart: UV = position / 2
      EXPECT_NEAR(t[0], 0.25, 1e-9);
      EXPECT_NEAR(t[1], 0.5, 1e-9);
    } else {
      ++right;  // across the seam: the right chart's coordinates at its nearest point, x = 1
      EXPECT_NEAR(t[0], 10.5, 1e-9);
      EXPECT_NEAR(t[1], 0.5, 1e-9);
    }
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
}
