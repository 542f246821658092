#pragma once
/** \file CornerAttributes.hh
 *  Per-corner attributes beyond the normal and the first UV set that the mesh traits carry: further UV
 *  sets and vertex colours, as optional named halfedge properties, one per set. Per corner (wedge) like
 *  UV0, so a welded vertex keeps a value per side of a seam.
 *
 *  | name            | kind     | type            |
 *  |-----------------|----------|-----------------|
 *  | "h:texcoord_n"  | halfedge | OpenMesh::Vec4f | UV set n >= 1: (u, v, 0, 0), origin bottom-left as UV0 |
 *  | "h:color_n"     | halfedge | OpenMesh::Vec4f | colour set n >= 0: RGBA in [0, 1] |
 *
 *  A halfedge's value belongs to its to-vertex in its face; border halfedges belong to no face and carry
 *  nothing meaningful. A mesh without a set carries no property for it; one that has a set has it on every
 *  corner (a part of the input without colours gets white, as glTF shows a primitive without COLOR_0).
 */

#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <OpenMesh/Core/Utils/Property.hh>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// Sets per kind that can be carried: assimp's AI_MAX_NUMBER_OF_TEXTURECOORDS and AI_MAX_NUMBER_OF_COLOR_SETS.
inline constexpr int kMaxTexCoordSets = 8;
inline constexpr int kMaxColorSets = 8;

enum class CornerKind { TexCoord, Color };

/// One carried set: its kind, its set index in the input (TEXCOORD_n / COLOR_n) and its property.
struct CornerChannel {
  CornerKind kind;
  int set;
  OpenMesh::HPropHandleT<OpenMesh::Vec4f> handle;
  /// The value a corner that the input gave no value has.
  OpenMesh::Vec4f fallback() const {
    return kind == CornerKind::Color ? OpenMesh::Vec4f(1, 1, 1, 1) : OpenMesh::Vec4f(0, 0, 0, 0);
  }
};

inline std::string corner_property_name(CornerKind kind, int set) {
  return (kind == CornerKind::Color ? "h:color_" : "h:texcoord_") + std::to_string(set);
}

/// Every set \p mesh carries: UV sets by index, then colour sets by index.
template <typename Mesh>
std::vector<CornerChannel> corner_channels(const Mesh& mesh) {
  std::vector<CornerChannel> out;
  for (const CornerKind kind : {CornerKind::TexCoord, CornerKind::Color})
    for (int set = kind == CornerKind::TexCoord ? 1 : 0;
         set < (kind == CornerKind::TexCoord ? kMaxTexCoordSets : kMaxColorSets); ++set) {
      CornerChannel c{kind, set, OpenMesh::HPropHandleT<OpenMesh::Vec4f>()};
      if (mesh.get_property_handle(c.handle, corner_property_name(kind, set))) out.push_back(c);
    }
  return out;
}

/// Finds or adds the set; a new one starts with the fallback value on every halfedge the mesh has.
template <typename Mesh>
CornerChannel add_corner_channel(Mesh& mesh, CornerKind kind, int set) {
  CornerChannel c{kind, set, OpenMesh::HPropHandleT<OpenMesh::Vec4f>()};
  const std::string name = corner_property_name(kind, set);
  if (mesh.get_property_handle(c.handle, name)) return c;
  mesh.add_property(c.handle, name);
  for (auto h : mesh.all_halfedges()) mesh.property(c.handle, h) = c.fallback();
  return c;
}

/// Copies every carried set's value of corner \p from to corner \p to (a face rebuilt elsewhere).
template <typename Mesh>
void copy_corner_channels(Mesh& mesh, typename Mesh::HalfedgeHandle from, typename Mesh::HalfedgeHandle to) {
  for (const CornerChannel& c : corner_channels(mesh)) mesh.property(c.handle, to) = mesh.property(c.handle, from);
}

}  // namespace OpenMeshSkinned
