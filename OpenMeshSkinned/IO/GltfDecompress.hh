#pragma once
/** \file GltfDecompress.hh
 *  Compressed and quantised glTF made plain before assimp 5.2 reads it. Internal to GltfRepair.
 *
 *  assimp 5.2 knows neither meshopt compression nor quantised attributes, and its Draco decoding fails on
 *  scenes with several Draco primitives. Decoding all three ourselves keeps one reading path:
 *  - `EXT_meshopt_compression` / `KHR_meshopt_compression` buffer views are decoded with Debian's
 *    meshoptimizer (0.18: vertex codec version 0, index codecs 0 and 1, the octahedral, quaternion and
 *    exponential filters) and their fallback buffers dropped;
 *  - `KHR_draco_mesh_compression` primitives are decoded with Debian's libdraco;
 *  - attributes stored as (normalised) integers (`KHR_mesh_quantization`) and integer animation outputs
 *    become floats with the values the spec gives them; the node transforms gltfpack adds to dequantise
 *    stay and keep working, and a `KHR_texture_transform` that only undoes a quantised `TEXCOORD` is
 *    folded into the coordinates (assimp would drop it).
 *  The decoded copy no longer declares these extensions.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

/// Throws IOError naming the first extension in "extensionsRequired" that the tool cannot honour.
void check_required_extensions(const nlohmann::json& doc, const std::string& shown_as);

/// Decodes everything listed in the file's comment above, then rewrites the animation samplers assimp
/// reads wrongly (GltfInterpolation.hh); returns the names of what it decoded or rewrote (empty: \p doc
/// is unchanged), and adds to \p notes one line per kind of sampler rewritten, for the user. Throws
/// IOError, one line naming the file and the part, for data that cannot be decoded (a meshopt vertex
/// codec newer than Debian's library, corrupt streams).
std::vector<std::string> decompress_gltf(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as,
                                         std::vector<std::string>& notes);

}  // namespace OpenMeshSkinned::detail
