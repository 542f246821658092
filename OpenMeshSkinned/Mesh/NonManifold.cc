#include "OpenMeshSkinned/Mesh/NonManifold.hh"

#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <vector>

namespace OpenMeshSkinned {

// Copies first: add_vertex may reallocate the arrays a reference into them would point at.
SkinnedMesh::VertexHandle copy_vertex(SkinnedMesh& mesh, SkinnedMesh::VertexHandle vh) {
  const auto h_inf = influences_handle(mesh);
  const SkinnedMesh::Point p = mesh.point(vh);
  const Influences inf = mesh.property(h_inf, vh);
  const auto copy = mesh.add_vertex(p);
  mesh.property(h_inf, copy) = inf;
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  if (morph_deltas_handle(mesh, hd)) {
    MorphDeltas d = mesh.property(hd, vh);
    mesh.property(hd, copy) = std::move(d);
  }
  return copy;
}

size_t split_nonmanifold_vertices(SkinnedMesh& mesh, OpenMesh::FPropHandleT<int> h_fmat) {
  size_t copies = 0;
  std::vector<std::vector<SkinnedMesh::FaceHandle>> faces_of(mesh.n_vertices());
  for (auto fh : mesh.faces())
    for (auto vh : mesh.fv_range(fh)) faces_of[vh.idx()].push_back(fh);
  struct Corner {
    SkinnedMesh::VertexHandle v;
    SkinnedMesh::Normal n;
    SkinnedMesh::TexCoord2D t;
    SkinnedMesh::HalfedgeHandle from;  // the corner in the deleted face: its storage outlives the deletion
  };
  for (size_t vi = 0; vi < faces_of.size(); ++vi) {
    const SkinnedMesh::VertexHandle vh(static_cast<int>(vi));
    if (mesh.status(vh).deleted() || mesh.is_manifold(vh)) continue;
    // Circulating the outgoing halfedges walks fan after fan; a boundary halfedge (no face) separates two.
    std::vector<SkinnedMesh::HalfedgeHandle> out;
    for (auto heh : mesh.voh_range(vh)) out.push_back(heh);
    const auto first_gap = std::find_if(out.begin(), out.end(), [&](auto h) { return mesh.is_boundary(h); });
    if (first_gap == out.end()) continue;
    std::rotate(out.begin(), first_gap, out.end());
    std::vector<std::vector<SkinnedMesh::FaceHandle>> fans;
    for (auto heh : out) {
      if (mesh.is_boundary(heh)) {
        fans.emplace_back();
        continue;
      }
      fans.back().push_back(mesh.face_handle(heh));
    }
    fans.erase(std::remove_if(fans.begin(), fans.end(), [](const auto& f) { return f.empty(); }), fans.end());
    for (size_t fi = 1; fi < fans.size(); ++fi) {
      const std::vector<SkinnedMesh::FaceHandle>& others = fans[fi];
      const auto copy = copy_vertex(mesh, vh);
      ++copies;
      for (auto fh : others) {
        std::vector<Corner> corners;
        for (auto heh : mesh.fh_range(fh)) {
          const SkinnedMesh::VertexHandle to = mesh.to_vertex_handle(heh);
          corners.push_back(
              {to == vh ? SkinnedMesh::VertexHandle(copy) : to, mesh.normal(heh), mesh.texcoord2D(heh), heh});
        }
        const int mat = mesh.property(h_fmat, fh);
        mesh.delete_face(fh, false);
        auto nf = mesh.add_face(corners[0].v, corners[1].v, corners[2].v);
        if (!nf.is_valid()) {
          for (Corner& c : corners) {
            c.v = copy_vertex(mesh, c.v);
            ++copies;
          }
          nf = mesh.add_face(corners[0].v, corners[1].v, corners[2].v);
        }
        faces_of.resize(mesh.n_vertices());
        mesh.property(h_fmat, nf) = mat;
        for (auto heh : mesh.fh_range(nf))
          for (const Corner& c : corners)
            if (c.v == mesh.to_vertex_handle(heh)) {
              mesh.set_normal(heh, c.n);
              mesh.set_texcoord2D(heh, c.t);
              copy_corner_channels(mesh, c.from, heh);
            }
        for (const Corner& c : corners) faces_of[c.v.idx()].push_back(nf);
      }
    }
  }
  return copies;
}

}  // namespace OpenMeshSkinned
