#pragma once
/** \file SkinnedMesh.hh
 *  The concrete mesh type the importer and exporter use. The decimater modules are templates and work on
 *  any OpenMesh triangle mesh (float or double points) that carries the skin properties.
 */

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace OpenMeshSkinned {

struct SkinnedTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using TexCoord2D = OpenMesh::Vec2f;
  // Seams: normals and UVs are per corner (wedge), so one welded vertex can carry several of each.
  HalfedgeAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::TexCoord2D | OpenMesh::Attributes::Status);
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
};

using SkinnedMesh = OpenMesh::TriMesh_ArrayKernelT<SkinnedTraits>;

/// Requests the dynamic attributes the importer, the generators and the decimater rely on.
inline void request_skinned_attributes(SkinnedMesh& mesh) {
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  mesh.request_halfedge_normals();
  mesh.request_halfedge_texcoords2D();
  mesh.request_face_normals();
}

/// Sets every corner normal and UV to zero. OpenMesh leaves per-halfedge attributes uninitialised, and
/// a generator that sets only some of them would otherwise export garbage (or NaN): zero normals are
/// recomputed on export, all-zero UVs are not written.
inline void clear_corner_attributes(SkinnedMesh& mesh) {
  for (auto heh : mesh.halfedges()) {
    mesh.set_normal(heh, SkinnedMesh::Normal(0, 0, 0));
    mesh.set_texcoord2D(heh, SkinnedMesh::TexCoord2D(0, 0));
  }
}

}  // namespace OpenMeshSkinned
