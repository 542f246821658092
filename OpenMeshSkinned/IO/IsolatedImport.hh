#pragma once
/** \file IsolatedImport.hh
 *  import_skinned() in a child process: the reader's crash, runaway allocation or endless loop costs the
 *  child, and the caller gets a one-line IOError. import_skinned() calls it when ImportOptions::isolate.
 */

#include "OpenMeshSkinned/IO/ImportOptions.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>

namespace OpenMeshSkinned {

/// What the child runs: import_skinned() passes detail::import_file (repair and decoding, then the reader).
using FileReader = ImportReport (*)(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt);

/** Forks; the child reads \p path with \p read,
 *  address-space limit opt.memory_limit_mb and sends the result back (ImportArchive); the parent kills it
 *  after opt.time_limit_seconds. Errors: "<path>: the reader crashed (SIGSEGV) reading it (format ...)",
 *  "... ran out of memory (limit N MB) ...", "... took longer than N s ...", or the child's own IOError. */
ImportReport import_isolated(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt, FileReader read);

}  // namespace OpenMeshSkinned
