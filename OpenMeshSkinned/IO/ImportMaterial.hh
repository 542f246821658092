#pragma once
/** \file ImportMaterial.hh
 *  The materials of an imported file as glTF materials: a glTF 2.0 file's as the file has them
 *  (GltfMaterials.hh), any other format's mapped from what assimp reports to glTF PBR in one place here.
 *  Used by import_skinned().
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <string>
#include <vector>

struct aiScene;
struct aiMaterial;

namespace OpenMeshSkinned {

/** One material per material of \p scene, in its order (the faces' material indices): for a glTF 2.0
 *  file \p read_path, the file's own materials (assimp appends a default material after them, which becomes
 *  the glTF default material); for any other file, read_material() of each. \p source is the file the user
 *  named (textures are looked for beside it). What cannot be kept adds a line to \p warnings. */
std::vector<Material> read_materials(const aiScene* scene, const std::string& source, const std::string& read_path,
                                     std::vector<std::string>& warnings);

/** \p m of \p scene mapped to glTF PBR: base colour (and its texture), opacity (a factor below 1 or an
 *  opacity map makes alphaMode BLEND; the map becomes the base colour's alpha), normal map (a height map
 *  only when its pixels are a normal map's), metallic/roughness factors and maps (packed into one
 *  texture; a glossiness map inverted), emissive colour and map, ambient occlusion (or a light map),
 *  two-sided. A texture that cannot be found or read, and a map glTF has no place for, adds a line to
 *  \p warnings and the material is kept without it. \p source is the file being read (its folder is where
 *  textures are looked for). */
Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source,
                       std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned
