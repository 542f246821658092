#pragma once
/** \file CheckLodOptions.hh
 *  Whether a request for LODs can be carried out, before any work: the command line's, the Python
 *  package's and make_lods()'s one check, with the command line's one-line messages.
 */

#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <string>

namespace OpenMeshSkinned {

/// Throws LodOptionsError when \p options cannot be right for any mesh.
void check_lod_options(const LodOptions& options);
/// Throws LodOptionsError when \p options cannot be carried out on \p mesh, named \p name in the message
/// (more faces asked for than it has, no such clip, more poses than max_memory_mb allows, ...).
void check_lod_options(const LodOptions& options, const SkinnedMesh& mesh, const std::string& name = "the mesh");

}  // namespace OpenMeshSkinned
