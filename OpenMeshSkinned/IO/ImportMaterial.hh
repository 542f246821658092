#pragma once
/** \file ImportMaterial.hh
 *  The materials of an imported file as glTF materials: a glTF 2.0 file's as the file has them
 *  (GltfMaterials.hh), any other format's mapped from what assimp reports to glTF PBR (AssimpMaterial.hh).
 *  Used by import_skinned().
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <string>
#include <vector>

struct aiScene;

namespace OpenMeshSkinned {

/** One material per material of \p scene, in its order (the faces' material indices): for a glTF 2.0
 *  file \p read_path, the file's own materials (assimp appends a default material after them, which becomes
 *  the glTF default material); for any other file, read_material() of each. \p source is the file the user
 *  named (textures are looked for beside it). What cannot be kept adds a line to \p warnings. */
std::vector<Material> read_materials(const aiScene* scene, const std::string& source, const std::string& read_path,
                                     std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned
