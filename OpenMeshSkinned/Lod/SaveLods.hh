#pragma once
// A LOD chain written as glTF files: one file per level, all of them or none.

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// Level \p i of \p n: \p output itself when there is one level, else NAME_lod1.glb, NAME_lod2.glb, ...
/// beside it (in the order of the chain: decreasing ratio).
std::string lod_file_path(const std::string& output, size_t i, size_t n);

/// What a LOD's glTF mesh node carries in its extras: its ratio and, when evaluated, its held-out error and
/// switch hints (SwitchHints.hh), for an engine importer to set its LOD thresholds from.
GltfNodeExtras lod_node_extras(const LodReport& report);

/** Writes every level of \p chain to its lod_file_path() (.glb or .gltf with its buffers embedded), all
 *  together at the end or none; never over one of \p inputs. Returns the paths written. Throws IOError
 *  (PathConflict for a clash) with nothing written. */
std::vector<std::string> save_lods(const LodChain& chain, const std::string& output,
                                   const std::vector<std::string>& inputs = {});

}  // namespace OpenMeshSkinned
