#pragma once
/** \file ImportMaterial.hh
 *  An assimp material as the exporter needs it: name, base colour and the base-colour image's bytes
 *  (embedded in the file, or read from beside it). Used by import_skinned().
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <string>
#include <vector>

struct aiScene;
struct aiMaterial;

namespace OpenMeshSkinned {

/// Reads \p m of \p scene; a texture that cannot be found or read adds a line to \p warnings and the
/// material is kept without it. \p source is the file being read (its folder is where textures are
/// looked for).
Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source,
                       std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned
