#pragma once
/** \file AssimpMaterial.hh
 *  One material as assimp reports it (any format but glTF 2.0, whose materials are read from the file
 *  itself: GltfMaterials.hh) mapped to glTF PBR in one place. Used by read_materials() (ImportMaterial.hh).
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <string>
#include <vector>

struct aiScene;
struct aiMaterial;

namespace OpenMeshSkinned {

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
