#pragma once
/** \file ExportMaterials.hh
 *  The materials of an exported glTF, their textures, samplers and images. Internal to the exporter
 *  (ExportGltf.cc); the public entry point is export_gltf().
 */

#include "OpenMeshSkinned/IO/GltfBuffer.hh"
#include "OpenMeshSkinned/Skin/Material.hh"

#include <vector>

namespace OpenMeshSkinned::detail {

/** Writes \p mats as model.materials, in their order (the primitives' material indices): each material's
 *  glTF object with its texture references renumbered into the model's textures; textures, samplers and
 *  images (inside the buffer, as they are) written once however many materials use them; the extensions
 *  they use declared in extensionsUsed, and in extensionsRequired where the input required them. Every
 *  texture reference's texCoord (and its KHR_texture_transform's) names the input's UV set: it becomes the
 *  written set's index, written_uv_index(\p uv_sets, set) (ExportParts.hh). */
void write_materials(const std::vector<Material>& mats, const std::vector<int>& uv_sets, BufferWriter& buf,
                     tinygltf::Model& model);

/** The input's UV set that \p m's tangent frames follow, -1 when it needs none (needs_tangent_space()): the
 *  normal map's (its KHR_texture_transform's texCoord when that overrides it), else an extension's normal
 *  map's (clearcoatNormalTexture), else KHR_materials_anisotropy's texture's; 0 when none names one. */
int tangent_uv_set(const Material& m);

}  // namespace OpenMeshSkinned::detail
