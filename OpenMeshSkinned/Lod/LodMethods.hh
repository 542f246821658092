#pragma once
// The decimation methods make_lods() offers (one table: validation, the CLI's --compare and help, and the
// modules all read it), and the LOD chain one of them builds in one pass.

#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodProgress.hh>
#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

struct LodMethod {
  const char* name;
  const char* help;  ///< what it is, for --help
};

/// Every method, the product first (the order of the CLI's --compare).
const std::vector<LodMethod>& lod_methods();
/// "skinned, decoro, dsd, rest, compact, frames, deform or static".
std::string lod_method_names();
bool is_lod_method(const std::string& name);

/// Most bones on any vertex of \p mesh.
int max_influences_of(const SkinnedMesh& mesh);

/** Decimates a copy of \p input, posed by \p examples, through every target in one pass (the
 *  multiresolution hierarchy: each level continues from the previous one) with \p method, and snapshots
 *  the mesh as it passes each target. The levels' reports have what the decimation knows (not the
 *  held-out error, keys or joints). */
std::vector<LodLevel> decimate_chain(const SkinnedMesh& input, const std::vector<Pose>& examples,
                                     const std::vector<size_t>& targets, const std::vector<double>& ratios,
                                     const LodOptions& options, const std::string& method,
                                     const LodCallbacks& callbacks = {});

/** Releases what only an exported mesh needs (corner normals and UVs, face normals) from a mesh that is
 *  from now on only the reference surface the LODs are fitted to and measured against. */
void keep_as_reference_only(SkinnedMesh& mesh);

}  // namespace OpenMeshSkinned
