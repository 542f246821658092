// UV re-interpolation after a collapse (Decimater/UvTransferT.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/UvTransferT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// A 3x3 vertex grid over [0,2]^2 with UV = position / 2, except that the right column of faces is a
// separate chart (a seam along x = 1) whose UVs are shifted by (+10, 0).
Mesh grid_with_seam() {
  Mesh mesh;
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  mesh.request_halfedge_texcoords2D();
  std::vector<Mesh::VertexHandle> v;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) v.push_back(mesh.add_vertex(Mesh::Point(k, i, 0)));
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      const auto a = v[i * 3 + k], b = v[i * 3 + k + 1], c = v[(i + 1) * 3 + k], d = v[(i + 1) * 3 + k + 1];
      for (auto fh : {mesh.add_face(a, b, d), mesh.add_face(a, d, c)})
        for (auto h : mesh.fh_range(fh)) {
          const auto p = mesh.point(mesh.to_vertex_handle(h));
          mesh.set_texcoord2D(h, Mesh::TexCoord2D(p[0] / 2 + (k == 1 ? 10 : 0), p[1] / 2));
        }
    }
  return mesh;
}

Mesh::HalfedgeHandle halfedge(const Mesh& mesh, Mesh::Point from, Mesh::Point to) {
  for (auto h : mesh.halfedges())
    if (mesh.point(mesh.from_vertex_handle(h)) == from && mesh.point(mesh.to_vertex_handle(h)) == to) return h;
  return Mesh::HalfedgeHandle();
}

}  // namespace

TEST(UvTransfer, AllZeroUvsAreNotBookkept) {
  Mesh mesh = grid_with_seam();
  for (auto h : mesh.halfedges()) mesh.set_texcoord2D(h, Mesh::TexCoord2D(0, 0));
  UvTransferT<Mesh> uv(mesh);
  uv.prepare();
  EXPECT_FALSE(uv.active());
}

TEST(UvTransfer, BorderHalfedgesDoNotCount) {
  // A border halfedge has no face; whatever its UV holds, the mesh has no UVs to keep.
  Mesh mesh = grid_with_seam();
  for (auto h : mesh.halfedges())
    mesh.set_texcoord2D(h, mesh.is_boundary(h) ? Mesh::TexCoord2D(3.5f, -1.0f) : Mesh::TexCoord2D(0, 0));
  UvTransferT<Mesh> uv(mesh);
  uv.prepare();
  EXPECT_FALSE(uv.active());
}

TEST(UvTransfer, AMovedVertexTakesTheUvOfWhereItLandsInItsOwnChart) {
  Mesh mesh = grid_with_seam();
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
