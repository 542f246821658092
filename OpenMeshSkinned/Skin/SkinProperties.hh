#pragma once
/** \file SkinProperties.hh
 *  Where the skin lives on an OpenMesh mesh: named properties, so any OpenMesh tool carries it along.
 *
 *  | name                 | kind   | type                   |
 *  |----------------------|--------|------------------------|
 *  | "v:skin_influences"  | vertex | Influences             |
 *  | "m:skeleton"         | mesh   | Skeleton               |
 *  | "m:skin_poses"       | mesh   | std::vector<Pose>      |  example poses the decimater judges error in
 *  | "m:animation_clips"  | mesh   | std::vector<Clip>      |
 *  | "m:materials"        | mesh   | std::vector<Material>  |
 *  | "f:material"         | face   | int (index into m:materials, -1 = none) |
 */

#include "OpenMeshSkinned/Skin/Influences.hh"
#include "OpenMeshSkinned/Skin/Material.hh"
#include "OpenMeshSkinned/Skin/Skeleton.hh"

#include <OpenMesh/Core/Utils/Property.hh>

#include <stdexcept>
#include <vector>

namespace OpenMeshSkinned {

namespace prop_names {
inline constexpr const char* kInfluences = "v:skin_influences";
inline constexpr const char* kSkeleton = "m:skeleton";
inline constexpr const char* kPoses = "m:skin_poses";
inline constexpr const char* kClips = "m:animation_clips";
inline constexpr const char* kMaterials = "m:materials";
inline constexpr const char* kFaceMaterial = "f:material";
}  // namespace prop_names

namespace detail {
template <typename Handle, typename Mesh>
Handle get_or_add(Mesh& mesh, const char* name) {
  Handle h;
  if (!mesh.get_property_handle(h, name)) mesh.add_property(h, name);
  return h;
}
template <typename Handle, typename Mesh>
Handle get_existing(const Mesh& mesh, const char* name) {
  Handle h;
  if (!mesh.get_property_handle(h, name))
    throw std::runtime_error(std::string("mesh has no skin property \"") + name + "\"");
  return h;
}
}  // namespace detail

/// Adds the skin properties to \p mesh if absent and returns the influence handle.
template <typename Mesh>
OpenMesh::VPropHandleT<Influences> add_skin(Mesh& mesh) {
  detail::get_or_add<OpenMesh::MPropHandleT<Skeleton>>(mesh, prop_names::kSkeleton);
  detail::get_or_add<OpenMesh::MPropHandleT<std::vector<Pose>>>(mesh, prop_names::kPoses);
  detail::get_or_add<OpenMesh::MPropHandleT<std::vector<Clip>>>(mesh, prop_names::kClips);
  detail::get_or_add<OpenMesh::MPropHandleT<std::vector<Material>>>(mesh, prop_names::kMaterials);
  detail::get_or_add<OpenMesh::FPropHandleT<int>>(mesh, prop_names::kFaceMaterial);
  return detail::get_or_add<OpenMesh::VPropHandleT<Influences>>(mesh, prop_names::kInfluences);
}

template <typename Mesh>
bool has_skin(const Mesh& mesh) {
  OpenMesh::VPropHandleT<Influences> h;
  OpenMesh::MPropHandleT<Skeleton> s;
  return mesh.get_property_handle(h, prop_names::kInfluences) && mesh.get_property_handle(s, prop_names::kSkeleton);
}

template <typename Mesh>
OpenMesh::VPropHandleT<Influences> influences_handle(const Mesh& mesh) {
  return detail::get_existing<OpenMesh::VPropHandleT<Influences>>(mesh, prop_names::kInfluences);
}

template <typename Mesh>
Skeleton& skeleton(Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<Skeleton>>(mesh, prop_names::kSkeleton))[0];
}
template <typename Mesh>
const Skeleton& skeleton(const Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<Skeleton>>(mesh, prop_names::kSkeleton))[0];
}

template <typename Mesh>
std::vector<Pose>& example_poses(Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<std::vector<Pose>>>(mesh, prop_names::kPoses))[0];
}
template <typename Mesh>
const std::vector<Pose>& example_poses(const Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<std::vector<Pose>>>(mesh, prop_names::kPoses))[0];
}

/** The example poses, for a module that judges collapses in them: std::invalid_argument when there are
 *  none. The reader sets none (a character's clips hold many poses, and which to use is the caller's
 *  choice); decimating in the bind pose alone must be asked for (use_bind_pose_only()). */
template <typename Mesh>
const std::vector<Pose>& required_example_poses(const Mesh& mesh) {
  const std::vector<Pose>& poses = example_poses(mesh);
  if (poses.empty())
    throw std::invalid_argument(
        "the mesh has no example poses: set example_poses(mesh) before initialize() (e.g. sample_poses_evenly over "
        "one of clips(mesh)), or call use_bind_pose_only(mesh) to decimate in the rest pose alone");
  return poses;
}
/// Makes the bind pose the only example pose: the mesh is decimated and judged in its rest pose alone.
template <typename Mesh>
void use_bind_pose_only(Mesh& mesh) {
  example_poses(mesh) = {Pose::identity(skeleton(mesh).size())};
}

template <typename Mesh>
std::vector<Clip>& clips(Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<std::vector<Clip>>>(mesh, prop_names::kClips))[0];
}
template <typename Mesh>
const std::vector<Clip>& clips(const Mesh& mesh) {
  return mesh.mproperty(detail::get_existing<OpenMesh::MPropHandleT<std::vector<Clip>>>(mesh, prop_names::kClips))[0];
}

template <typename Mesh>
std::vector<Material>& materials(Mesh& mesh) {
  return mesh.mproperty(
      detail::get_existing<OpenMesh::MPropHandleT<std::vector<Material>>>(mesh, prop_names::kMaterials))[0];
}
template <typename Mesh>
const std::vector<Material>& materials(const Mesh& mesh) {
  return mesh.mproperty(
      detail::get_existing<OpenMesh::MPropHandleT<std::vector<Material>>>(mesh, prop_names::kMaterials))[0];
}

template <typename Mesh>
OpenMesh::FPropHandleT<int> face_material_handle(const Mesh& mesh) {
  return detail::get_existing<OpenMesh::FPropHandleT<int>>(mesh, prop_names::kFaceMaterial);
}

}  // namespace OpenMeshSkinned
