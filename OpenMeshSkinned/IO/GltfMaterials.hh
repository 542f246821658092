#pragma once
/** \file GltfMaterials.hh
 *  A glTF 2.0 file's materials read from the file itself, as it has them: assimp 5.2 keeps only part of a
 *  glTF material (no KHR_materials_* extensions, texture transforms, samplers or KTX2/WebP images).
 *  Used by read_materials().
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <set>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** Every material of the glTF 2.0 file \p read_path, in the file's order: the material object as it is
 *  (factors, alpha, doubleSided, extras, every extension), each texture it references (directly or from an
 *  extension) with its sampler and its images' bytes as they are. Images outside the file are looked for
 *  beside \p source (the file the user named; \p read_path may be a repaired copy of it), as read_texture_file()
 *  does. A texture that cannot be read adds one line to \p warnings and the materials that use it are kept
 *  without it. \p reader_order gets the file's material indices in the order assimp 5.2's glTF reader
 *  numbers them: it reads materials as it first meets them (scene nodes depth first, each node's children
 *  before its own mesh; then the skins' joints and the animations' target nodes) and never reads the
 *  others. Returns false, leaving \p out alone, when the file is not glTF 2.0 or its materials cannot be
 *  parsed (\p warnings then says why, for a glTF file). */
bool read_gltf_materials(const std::string& read_path, const std::string& source, std::vector<Material>& out,
                         std::vector<int>& reader_order, std::vector<std::string>& warnings);

/** Whether \p m needs its primitives to carry tangents (the glTF validator's rule): a normal map, or a
 *  normal map of an extension (KHR_materials_clearcoat's clearcoatNormalTexture), or
 *  KHR_materials_anisotropy. A mesh writer generates them (MikkTSpace) where the input has none. */
bool needs_tangent_space(const Material& m);

/// Adds to \p names the name of every extension the glTF JSON \p json_text uses (every "extensions" object's keys).
void gltf_extension_names(const std::string& json_text, std::set<std::string>& names);

}  // namespace OpenMeshSkinned
