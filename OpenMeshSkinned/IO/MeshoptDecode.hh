#pragma once
/** \file MeshoptDecode.hh
 *  `EXT_meshopt_compression` / `KHR_meshopt_compression` buffer views decoded with Debian's meshoptimizer,
 *  which assimp 5.2 cannot read (see GltfDecompress.hh). Internal to the importer.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>

namespace OpenMeshSkinned::detail {

/// The extension's two names (EXT_ and KHR_), decoded alike.
extern const char* const kMeshoptExtensions[2];

/** Decodes every compressed buffer view of \p doc in place: each then points at its decoded bytes (added
 *  through \p bytes) and no longer carries the extension. False when there was none. Throws IOError,
 *  naming \p shown_as and the view, for a stream Debian's meshoptimizer cannot decode or a broken file. */
bool decode_meshopt(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as);

/** Drops the buffers that only stood in for compressed data once nothing refers to them, and renumbers
 *  the views' buffers. Last: \p bytes knows the buffers by their numbers until every view is decoded. */
void drop_fallback_buffers(nlohmann::json& doc);

}  // namespace OpenMeshSkinned::detail
