#pragma once
/** \file GltfJson.hh
 *  Checked look-ups and extension bookkeeping on a glTF document's JSON, which every decoding pass of
 *  GltfDecompress.hh does the same way. Internal to the importer.
 */

#include <nlohmann/json.hpp>

#include <string>

namespace OpenMeshSkinned::detail {

/// Removes extension \p name from \p object, and its "extensions" when that becomes empty.
void erase_extension(nlohmann::json& object, const std::string& name);

/// Removes \p name from the document's "extensionsUsed" and "extensionsRequired" (each dropped when empty).
void undeclare(nlohmann::json& doc, const std::string& name);

/// Whether \p name is in the document's "extensionsUsed" or "extensionsRequired".
bool declared(const nlohmann::json& doc, const std::string& name);

/// The document's top-level array \p name, made an empty one when it is missing or not an array.
nlohmann::json& array_of(nlohmann::json& doc, const char* name);

/// \p object's index \p key, below \p size; throws IOError naming \p what when it is missing or out of range.
size_t index_in(const nlohmann::json& object, const char* key, size_t size, const std::string& what);

}  // namespace OpenMeshSkinned::detail
