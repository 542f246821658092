#pragma once
/** \file GlbFile.hh
 *  The two things every glTF pass of the importer reads the same way (the repair and decoding, the
 *  material reader): a GLB's chunks and a URI's %XX escapes. Internal to the importer.
 */

#include <filesystem>
#include <string>

namespace OpenMeshSkinned::detail {

/// A GLB's chunks as it stores them.
struct GlbChunks {
  std::string json;  ///< the JSON chunk's text
  std::string bin;   ///< the binary chunk's payload (empty when has_bin is false)
  bool has_bin = false;
  std::string rest;  ///< every chunk after those two, byte for byte
};

/** Splits \p data, a GLB file's bytes; false when it is none (no "glTF" magic, or a JSON chunk that is
 *  missing or reaches past the end). A binary chunk that reaches past the end counts as none. */
bool split_glb(const std::string& data, GlbChunks& out);

/** The bytes of the file at \p path in \p out, read in one piece (a character-by-character stream read of
 *  a 12 MB GLB took a tenth of a second, twice per import); false, \p out empty, when it cannot be read. */
bool read_file_bytes(const std::filesystem::path& path, std::string& out);

/// \p uri with its %XX escapes decoded (a file name as the file system knows it).
std::string percent_decoded(const std::string& uri);

}  // namespace OpenMeshSkinned::detail
