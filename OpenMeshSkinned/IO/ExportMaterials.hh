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
 *  they use declared in extensionsUsed, and in extensionsRequired where the input required them. */
void write_materials(const std::vector<Material>& mats, BufferWriter& buf, tinygltf::Model& model);

}  // namespace OpenMeshSkinned::detail
