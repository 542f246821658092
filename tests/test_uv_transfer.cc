// Corner re-interpolation after a collapse (Collapse/CornerTransferT.hh, used as UvTransferT).
#include "helpers.hh"

#include <OpenMeshSkinned/Collapse/UvTransferT.hh>
#include <OpenMeshSkinned/Mesh/CornerAttributes.hh>

#include <algorithm>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

Mesh::HalfedgeHandle halfedge(const Mesh& mesh, Mesh::Point from, Mesh::Point to) {
  for (auto h : mesh.halfedges())
    if (mesh.point(mesh.from_vertex_handle(h)) == from && mesh.point(mesh.to_vertex_handle(h)) == to) return h;
  return Mesh::HalfedgeHandle();
}

// Collapses the left-column centre vertex (0,1) into the centre (1,1) around \p transfer, moving the
// survivor to \p to first; returns the survivor.
Mesh::VertexHandle collapse_left_centre(Mesh& mesh, UvTransferT<Mesh>& transfer, const Mesh::Point& to) {
  transfer.prepare();
  EXPECT_TRUE(transfer.active());
  const auto h = halfedge(mesh, Mesh::Point(0, 1, 0), Mesh::Point(1, 1, 0));
  EXPECT_TRUE(h.is_valid());
  const auto v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  transfer.record(v0, v1);
  mesh.collapse(h);
  mesh.set_point(v1, to);
  transfer.apply(v1);
  return v1;
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
  // The survivor moves to (0.5, 1).
  const auto v1 = collapse_left_centre(mesh, uv, Mesh::Point(0.5, 1, 0));
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

TEST(UvTransfer, EverySetIsReinterpolatedWithinItsOwnCharts) {
  // UV0 is one chart here; a colour boundary and a second UV set's seam run along x = 1. Moving the
  // collapsed vertex to x = 0.5 must interpolate UV0 and UV1 where it lands, and leave every corner's
  // colour on its own side of the boundary unblended.
  Mesh mesh = omsk_test::grid_with_uv_seam();
  const CornerChannel colour = add_corner_channel(mesh, CornerKind::Color, 0);
  const CornerChannel uv1 = add_corner_channel(mesh, CornerKind::TexCoord, 1);
  for (auto fh : mesh.faces()) {
    bool left = true;
    for (auto v : mesh.fv_range(fh)) left = left && mesh.point(v)[0] <= 1.0;
    for (auto h : mesh.fh_range(fh)) {
      const auto p = mesh.point(mesh.to_vertex_handle(h));
      mesh.set_texcoord2D(h, Mesh::TexCoord2D(p[0] / 2, p[1] / 2));
      mesh.property(colour.handle, h) =
          left ? OpenMesh::Vec4f(float(p[1] / 2), 0, 0, 1) : OpenMesh::Vec4f(0, 0, float(p[1] / 2), 0.5f);
      mesh.property(uv1.handle, h) = OpenMesh::Vec4f(float(p[0] / 4) + (left ? 0.f : 0.5f), float(p[1] / 4), 0, 0);
    }
  }
  UvTransferT<Mesh> transfer(mesh);
  const auto v1 = collapse_left_centre(mesh, transfer, Mesh::Point(0.5, 1, 0));
  int left = 0, right = 0;
  for (auto hi : mesh.vih_range(v1)) {
    if (mesh.is_boundary(hi)) continue;
    const auto t = mesh.texcoord2D(hi);
    EXPECT_NEAR(t[0], 0.25, 1e-6);  // one chart: where it landed
    EXPECT_NEAR(t[1], 0.5, 1e-6);
    const OpenMesh::Vec4f c = mesh.property(colour.handle, hi), u = mesh.property(uv1.handle, hi);
    if (c[3] == 1.0f) {
      ++left;  // the red side's colour and UV1 at x = 0.5
      EXPECT_NEAR(c[0], 0.5, 1e-6);
      EXPECT_EQ(c[2], 0.0f);
      EXPECT_NEAR(u[0], 0.125, 1e-6);
    } else {
      ++right;  // the blue side's, at its nearest point x = 1: no red mixed in
      EXPECT_EQ(c[3], 0.5f);
      EXPECT_EQ(c[0], 0.0f);
      EXPECT_NEAR(c[2], 0.5, 1e-6);
      EXPECT_NEAR(u[0], 0.75, 1e-6);
    }
    EXPECT_NEAR(u[1], 0.25, 1e-6);
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
}

TEST(UvTransfer, TheFacesBeyondTheCollapsedEdgeKeepTheirOwnValuesAtTheFarCorners) {
  // Every lower triangle of a grid cell red, every upper one blue: each edge is a colour boundary. The
  // collapse hands the surviving halfedge of each vanished triangle to the face beyond it, with the
  // vanished triangle's colour; after apply() every face still has one colour at all three corners.
  Mesh mesh = omsk_test::grid_with_uv_seam();
  const CornerChannel colour = add_corner_channel(mesh, CornerKind::Color, 0);
  for (auto fh : mesh.faces()) {
    // (a, b, d) faces have two vertices on their cell's bottom row, (a, d, c) faces two on its top row.
    std::vector<double> ys;
    for (auto v : mesh.fv_range(fh)) ys.push_back(mesh.point(v)[1]);
    std::sort(ys.begin(), ys.end());
    const bool lower = ys[0] == ys[1];
    for (auto h : mesh.fh_range(fh))
      mesh.property(colour.handle, h) = lower ? OpenMesh::Vec4f(1, 0, 0, 1) : OpenMesh::Vec4f(0, 0, 1, 1);
  }
  UvTransferT<Mesh> transfer(mesh);
  collapse_left_centre(mesh, transfer, Mesh::Point(1, 1, 0));  // where it was
  for (auto fh : mesh.faces()) {
    std::vector<OpenMesh::Vec4f> c;
    for (auto hi : mesh.fh_range(fh)) c.push_back(mesh.property(colour.handle, hi));
    EXPECT_TRUE(c[0] == c[1] && c[1] == c[2]) << "face " << fh.idx() << ": " << c[0] << " | " << c[1] << " | " << c[2];
  }
}
