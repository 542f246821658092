#pragma once
/** \file DracoDecode.hh
 *  `KHR_draco_mesh_compression` primitives decoded with Debian's libdraco: assimp 5.2's own Draco decoding
 *  fails on scenes with several Draco primitives (see GltfDecompress.hh). Internal to the importer.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>

namespace OpenMeshSkinned::detail {

extern const char* const kDracoExtension;

/** Decodes every Draco primitive of \p doc: its indices and the attributes its extension lists go to new
 *  buffer views (through \p bytes) in the types their accessors declare, an attribute's bounds made the
 *  decoded values' (the indices' dropped); an accessor two primitives share is copied so that each gets
 *  its own. False when there was none. Throws IOError, naming \p shown_as and the primitive, for data
 *  that cannot be decoded. */
bool decode_draco(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as);

}  // namespace OpenMeshSkinned::detail
