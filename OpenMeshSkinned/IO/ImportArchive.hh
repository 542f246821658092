#pragma once
/** \file ImportArchive.hh
 *  An imported character (mesh, skin, skeleton, clips, materials, morph targets) and its ImportReport as
 *  bytes and back. It is how the isolated importer hands its result across a process boundary, so it
 *  carries everything import_skinned() produces, exactly (bit-identical numbers).
 */

#include "OpenMeshSkinned/IO/ImportOptions.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>

namespace OpenMeshSkinned {

std::string save_import(const SkinnedMesh& mesh, const ImportReport& report);
/// As save_import(), appended to \p out (no copy of the archive: a large character's is tens of MB).
void append_import(const SkinnedMesh& mesh, const ImportReport& report, std::string& out);

/// Rebuilds \p mesh (cleared first) and \p report; throws IOError when \p bytes are not an archive.
void load_import(const std::string& bytes, SkinnedMesh& mesh, ImportReport& report);
/// As load_import(), from the \p size bytes at \p data (read in place).
void load_import(const char* data, size_t size, SkinnedMesh& mesh, ImportReport& report);

}  // namespace OpenMeshSkinned
