#pragma once
/** \file Seams.hh
 *  Attribute seams of a welded mesh: interior edges where what the surface shows is cut even though the
 *  surface is not — a boundary between two materials, a UV seam (the edge of a texture chart) on a
 *  textured material, a colour boundary (vertex colours that differ across the edge), or a hard edge
 *  (corner normals the exporter keeps apart). A collapse that drags such
 *  an edge sideways moves a colour boundary, tears the texture or moves the crease, even where the geometry
 *  is flat.
 */

#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <vector>

namespace OpenMeshSkinned {

/// Corner UVs (and colours) closer than this (in texture units, colour units) are the same; corner normals whose cosine
/// is below kHardEdgeNormalCos are a hard edge (the rule the exporter's corner normals follow).
inline constexpr double kSeamUvTolerance = 1e-6;
inline constexpr double kHardEdgeNormalCos = 0.5;

/** One flag per edge of \p mesh: whether it is an attribute seam. An interior edge is one when its two faces
 *  have different materials ("f:material"), or when at one of its end vertices the corners of the two faces
 *  carry UVs further apart than kSeamUvTolerance — counted only where one of the faces' materials has a
 *  texture (untextured UVs show nothing; without material properties every UV counts; every UV set of
 *  CornerAttributes.hh alike), or colours (always: a viewer multiplies every material by them) — or
 *  normals more than 60° apart. Border edges are no seams (they already are the surface's outline); all-zero attributes
 *  (as generated meshes carry them) never differ. */
template <typename Mesh>
std::vector<char> attribute_seams(const Mesh& mesh) {
  std::vector<char> seam(mesh.n_edges(), 0);
  OpenMesh::FPropHandleT<int> h_mat;
  OpenMesh::MPropHandleT<std::vector<Material>> h_mats;
  const bool has_materials = mesh.get_property_handle(h_mat, prop_names::kFaceMaterial) &&
                             mesh.get_property_handle(h_mats, prop_names::kMaterials);
  auto material = [&](typename Mesh::FaceHandle fh) { return has_materials ? mesh.property(h_mat, fh) : -1; };
  auto textured = [&](int m) {
    if (!has_materials) return true;
    const std::vector<Material>& mats = mesh.property(h_mats);
    return m >= 0 && m < int(mats.size()) && !mats[m].base_color_texture.empty();
  };
  const std::vector<CornerChannel> channels = corner_channels(mesh);
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh)) continue;
    const auto h0 = mesh.halfedge_handle(eh, 0), h1 = mesh.halfedge_handle(eh, 1);
    const int m0 = material(mesh.face_handle(h0)), m1 = material(mesh.face_handle(h1));
    if (m0 != m1) {
      seam[eh.idx()] = 1;
      continue;
    }
    const bool tex = textured(m0), uvs = mesh.has_halfedge_texcoords2D() && tex;
    // A halfedge's attributes belong to its to-vertex in its face: h0 carries b's corner of the first face,
    // prev(h1) b's corner of the second face, and the other way round for a.
    const typename Mesh::HalfedgeHandle corners[2][2] = {{h0, mesh.prev_halfedge_handle(h1)},
                                                         {h1, mesh.prev_halfedge_handle(h0)}};
    for (const auto& c : corners) {
      if (uvs) {
        const auto d = mesh.texcoord2D(c[0]) - mesh.texcoord2D(c[1]);
        if (double(d[0]) * d[0] + double(d[1]) * d[1] > kSeamUvTolerance * kSeamUvTolerance) seam[eh.idx()] = 1;
      }
      for (const CornerChannel& ch : channels) {
        if (ch.kind == CornerKind::TexCoord && !tex) continue;
        const auto d = mesh.property(ch.handle, c[0]) - mesh.property(ch.handle, c[1]);
        if (double(d.sqrnorm()) > kSeamUvTolerance * kSeamUvTolerance) seam[eh.idx()] = 1;
      }
      if (mesh.has_halfedge_normals()) {
        const auto n0 = mesh.normal(c[0]), n1 = mesh.normal(c[1]);
        const double l = double(n0.norm()) * n1.norm();
        if (l > 0.0 && double(n0 | n1) < kHardEdgeNormalCos * l) seam[eh.idx()] = 1;
      }
    }
  }
  return seam;
}

}  // namespace OpenMeshSkinned
