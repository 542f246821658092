#pragma once
/** \file Morph.hh
 *  Morph targets (blend shapes) on an OpenMesh mesh, as optional named properties:
 *
 *  | name               | kind   | type                     |
 *  |--------------------|--------|--------------------------|
 *  | "m:morph_targets"  | mesh   | std::vector<MorphTarget> |
 *  | "v:morph_deltas"   | vertex | MorphDeltas (one offset per target, rest space) |
 *
 *  As in glTF, a pose's morph weights m_i add sum_i m_i * delta_i to the rest position before skinning.
 *  Meshes without morph targets carry neither property.
 *
 *  Normal offsets are not stored: a target whose input had them (MorphTarget::normals) gets them on
 *  export, recomputed per corner as the normal of the morphed geometry minus the normal of the rest
 *  geometry, with the rest normals' smoothing groups. The exporter recomputes the rest normals from the
 *  LOD's geometry too, so only offsets made the same way make rest + offset the normal of the LOD's morphed
 *  surface; the input's offsets, carried over, would belong to the input's normals and shade a decimated
 *  (or re-smoothed) surface with the shape change of another one.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"

#include <OpenMesh/Core/Utils/Property.hh>

#include <Eigen/Core>

#include <vector>

namespace OpenMeshSkinned {

using MorphDeltas = std::vector<Eigen::Vector3f>;

namespace prop_names {
inline constexpr const char* kMorphTargets = "m:morph_targets";
inline constexpr const char* kMorphDeltas = "v:morph_deltas";
}  // namespace prop_names

/// Adds (or finds) the morph properties; returns the per-vertex delta handle.
template <typename Mesh>
OpenMesh::VPropHandleT<MorphDeltas> add_morph_targets(Mesh& mesh) {
  OpenMesh::MPropHandleT<std::vector<MorphTarget>> ht;
  if (!mesh.get_property_handle(ht, prop_names::kMorphTargets)) mesh.add_property(ht, prop_names::kMorphTargets);
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  if (!mesh.get_property_handle(hd, prop_names::kMorphDeltas)) mesh.add_property(hd, prop_names::kMorphDeltas);
  return hd;
}

/// True when \p mesh carries morph targets; \p h is then the per-vertex delta handle.
template <typename Mesh>
bool morph_deltas_handle(const Mesh& mesh, OpenMesh::VPropHandleT<MorphDeltas>& h) {
  return mesh.get_property_handle(h, prop_names::kMorphDeltas);
}

/// The mesh's morph targets (empty when it has none).
template <typename Mesh>
const std::vector<MorphTarget>& morph_targets(const Mesh& mesh) {
  static const std::vector<MorphTarget> none;
  OpenMesh::MPropHandleT<std::vector<MorphTarget>> h;
  return mesh.get_property_handle(h, prop_names::kMorphTargets) ? mesh.mproperty(h)[0] : none;
}
template <typename Mesh>
std::vector<MorphTarget>& morph_targets(Mesh& mesh) {
  OpenMesh::MPropHandleT<std::vector<MorphTarget>> h;
  if (!mesh.get_property_handle(h, prop_names::kMorphTargets)) mesh.add_property(h, prop_names::kMorphTargets);
  return mesh.mproperty(h)[0];
}

/// \p rest moved by the morph offsets \p deltas at \p weights.
inline Eigen::Vector3d apply_morph(Eigen::Vector3d rest, const MorphDeltas& deltas,
                                   const std::vector<double>& weights) {
  const size_t n = std::min(deltas.size(), weights.size());
  for (size_t i = 0; i < n; ++i)
    if (weights[i] != 0.0) rest += weights[i] * deltas[i].cast<double>();
  return rest;
}

}  // namespace OpenMeshSkinned
