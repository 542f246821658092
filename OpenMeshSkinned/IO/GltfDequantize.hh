#pragma once
/** \file GltfDequantize.hh
 *  Attributes stored as (normalised) integers (`KHR_mesh_quantization`) and integer animation outputs made
 *  floats, which assimp 5.2 cannot read (see GltfDecompress.hh). Internal to the importer.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>

namespace OpenMeshSkinned::detail {

/** Rewrites every integer accessor of a mesh attribute (but JOINTS_n), a morph target or an animation
 *  output as floats with the values the spec gives them. A `KHR_texture_transform` that every texture of a
 *  material reading a quantised TEXCOORD_n carries alike (gltfpack's dequantisation) is folded into the
 *  coordinates, and dropped from the materials. False when no accessor was an integer one. */
bool dequantize(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as);

}  // namespace OpenMeshSkinned::detail
