// Attribute seams (Mesh/Seams.hh): UV seams and hard edges of a welded mesh.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/CornerAttributes.hh>
#include <OpenMeshSkinned/Mesh/Seams.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <algorithm>
#include <cmath>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// omsk_test::grid_with_uv_seam(), its border halfedges holding a UV no face owns.
Mesh grid_with_seam() {
  Mesh mesh = omsk_test::grid_with_uv_seam();
  for (auto h : mesh.halfedges())
    if (mesh.is_boundary(h)) mesh.set_texcoord2D(h, Mesh::TexCoord2D(-7, -7));
  return mesh;
}

std::vector<std::pair<double, double>> seam_midpoints(const Mesh& mesh) {
  std::vector<std::pair<double, double>> mids;
  const std::vector<char> seams = attribute_seams(mesh);
  for (auto eh : mesh.edges())
    if (seams[eh.idx()]) {
      const auto h = mesh.halfedge_handle(eh, 0);
      const auto m = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
      mids.emplace_back(m[0], m[1]);
    }
  std::sort(mids.begin(), mids.end());
  return mids;
}

}  // namespace

TEST(Seams, TheEdgesBetweenTwoUvChartsAreTheSeam) {
  const Mesh mesh = grid_with_seam();
  // Only the two interior edges on x = 1 separate the charts; the chart's border halfedges (whatever they
  // hold) and the edges inside each chart are no seam.
  const std::vector<std::pair<double, double>> expected = {{1.0, 0.5}, {1.0, 1.5}};
  EXPECT_EQ(seam_midpoints(mesh), expected);
}

TEST(Seams, WithoutAttributesThereIsNoSeam) {
  Mesh zero = grid_with_seam();
  clear_corner_attributes(zero);
  EXPECT_TRUE(seam_midpoints(zero).empty());
}

TEST(Seams, UvsCountOnTexturedMaterialsAndMaterialsAlwaysDo) {
  Mesh mesh = grid_with_seam();
  add_skin(mesh);
  materials(mesh) = {Material{}, Material{}};
  const auto h_mat = face_material_handle(mesh);
  for (auto fh : mesh.faces()) mesh.property(h_mat, fh) = 0;
  // The UV seam of an untextured material shows nothing.
  EXPECT_TRUE(seam_midpoints(mesh).empty());
  const std::vector<std::pair<double, double>> x1 = {{1.0, 0.5}, {1.0, 1.5}};
  materials(mesh)[0].base_color_texture = "skin.png";
  EXPECT_EQ(seam_midpoints(mesh), x1);
  // Where two materials meet, the colour changes: a seam without any UV (here: the faces with y > 1).
  clear_corner_attributes(mesh);
  for (auto fh : mesh.faces()) {
    bool top = true;
    for (auto v : mesh.fv_range(fh)) top = top && mesh.point(v)[1] >= 1.0;
    mesh.property(h_mat, fh) = top ? 1 : 0;
  }
  const std::vector<std::pair<double, double>> y1 = {{0.5, 1.0}, {1.5, 1.0}};
  EXPECT_EQ(seam_midpoints(mesh), y1);
}

TEST(Seams, AHardEdgeIsASeamASoftOneIsNot) {
  Mesh mesh = grid_with_seam();
  for (auto h : mesh.halfedges()) mesh.set_texcoord2D(h, Mesh::TexCoord2D(0, 0));
  // Tilt the normals of the face corners with x < 1 (the left column of faces): by 30° the shading stays
  // smooth across x = 1 (the exporter would average it), by 80° the edge is hard.
  auto tilt = [&](double degrees) {
    const double a = degrees * M_PI / 180.0;
    for (auto fh : mesh.faces()) {
      bool left = true;
      for (auto v : mesh.fv_range(fh)) left = left && mesh.point(v)[0] <= 1.0;
      if (!left) continue;
      for (auto h : mesh.fh_range(fh)) mesh.set_normal(h, Mesh::Normal(-std::sin(a), 0, std::cos(a)));
    }
  };
  tilt(30);
  EXPECT_TRUE(seam_midpoints(mesh).empty());
  tilt(80);
  const std::vector<std::pair<double, double>> expected = {{1.0, 0.5}, {1.0, 1.5}};
  EXPECT_EQ(seam_midpoints(mesh), expected);
}

TEST(Seams, AColourBoundaryIsASeamOnEveryMaterialAUvSetOnlyOnATexturedOne) {
  Mesh mesh = grid_with_seam();
  clear_corner_attributes(mesh);
  add_skin(mesh);
  materials(mesh) = {Material{}};
  const auto h_mat = face_material_handle(mesh);
  for (auto fh : mesh.faces()) mesh.property(h_mat, fh) = 0;
  // Red on the faces with y > 1, blue below: the edges on y = 1 are a colour boundary, textured or not.
  const CornerChannel colour = add_corner_channel(mesh, CornerKind::Color, 0);
  const CornerChannel uv1 = add_corner_channel(mesh, CornerKind::TexCoord, 1);
  EXPECT_TRUE(seam_midpoints(mesh).empty()) << "a new set is uniform: no seam";
  for (auto fh : mesh.faces()) {
    bool top = true;
    for (auto v : mesh.fv_range(fh)) top = top && mesh.point(v)[1] >= 1.0;
    for (auto h : mesh.fh_range(fh))
      mesh.property(colour.handle, h) = top ? OpenMesh::Vec4f(1, 0, 0, 1) : OpenMesh::Vec4f(0, 0, 1, 1);
  }
  const std::vector<std::pair<double, double>> y1 = {{0.5, 1.0}, {1.5, 1.0}};
  EXPECT_EQ(seam_midpoints(mesh), y1);
  // A second UV set with a chart edge on x = 1 shows only once the material has a texture.
  for (auto fh : mesh.faces()) {
    bool left = true;
    for (auto v : mesh.fv_range(fh)) left = left && mesh.point(v)[0] <= 1.0;
    for (auto h : mesh.fh_range(fh)) mesh.property(uv1.handle, h) = OpenMesh::Vec4f(left ? 0.f : 0.5f, 0, 0, 0);
  }
  EXPECT_EQ(seam_midpoints(mesh), y1);
  materials(mesh)[0].base_color_texture = "skin.png";
  const std::vector<std::pair<double, double>> both = {{0.5, 1.0}, {1.0, 0.5}, {1.0, 1.5}, {1.5, 1.0}};
  EXPECT_EQ(seam_midpoints(mesh), both);
}
