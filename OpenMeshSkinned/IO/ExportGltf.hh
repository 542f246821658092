#pragma once
/** \file ExportGltf.hh
 *  Writes a skinned mesh as glTF 2.0: skeleton nodes with their names and hierarchy, one skin with
 *  inverse bind matrices, JOINTS/WEIGHTS (a second set when a vertex keeps more than four bones),
 *  normals and UVs split back into glTF vertices at seams, one primitive per material, the materials,
 *  and every animation clip.
 */

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>
#include <utility>
#include <vector>

namespace OpenMeshSkinned {

/** Named float vertex property the exporter writes as the application-specific attribute "_ERROR" when the
 *  mesh has it (the report page colours vertices by it); the LOD files the tool writes do not carry it. */
inline constexpr const char* kVertexErrorProperty = "v:omsk_error";

/** Writes \p mesh to \p path: binary .glb, or .gltf with the buffers embedded so the file stands alone.
 *  The file appears complete or not at all (written beside the target, then renamed).
 *  Throws IOError when the extension is neither, the folder is not writable, or the skin is invalid. */
void export_gltf(const SkinnedMesh& mesh, const std::string& path);

/// Numbers for the mesh node's `extras` (e.g. a LOD's switch hints), name and value.
using GltfNodeExtras = std::vector<std::pair<std::string, double>>;
/// As export_gltf(mesh, path), the mesh node carrying \p node_extras.
void export_gltf(const SkinnedMesh& mesh, const std::string& path, const GltfNodeExtras& node_extras);

}  // namespace OpenMeshSkinned
