#pragma once
// The decimation methods the tool offers (one table: validation, --compare, help and the modules all
// read it) and the LOD chain built with one of them.

#include "Options.hh"

#include <OpenMeshSkinned/Skin/Skeleton.hh>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace skinned_decimate {

struct Method {
  const char* name;
  const char* help;  // what it is, for --help
};

/// Every method, the product first: the order of --compare.
const std::vector<Method>& methods();
/// "skinned, decoro, dsd, rest, compact or static".
std::string method_names();
bool is_method(const std::string& name);

/// Most bones on any vertex of \p mesh.
int max_influences_of(const Mesh& mesh);

/// One level of a chain as measured.
struct Lod {
  double ratio = 0.0;
  size_t target = 0;  // triangles asked for
  size_t faces = 0, vertices = 0;
  double seconds = 0.0;
  int max_influences = 0;
  size_t keys = 0;                    // key frames over its clips' channels (fewer with --anim-error)
  int joints = 0;                     // its skeleton's joints (fewer with --max-joints)
  double fold_limit = 90.0;           // the largest face turn allowed to reach the target (degrees)
  bool at_floor = false;              // stopped above the target where no collapse keeps the mesh manifold
  size_t pieces = 0;                  // then: its connected pieces
  size_t fold_fallbacks = 0;          // collapses made off their solved placement, which folded, to reach it
  size_t non_finite_weights = 0;      // weight problems the solver refused as non-finite, this level and before
  double deviation_bound = -1.0;      // --max-error: bound on the original's vertices' distance, % (< 0: none)
  bool evaluated = false;             // false with --no-eval
  double rms = 0.0, hausdorff = 0.0;  // % of the rest-pose bounding-box diagonal
  std::vector<float> vertex_error;    // per vertex, max over held-out frames, % of the diagonal (--html)
  std::string file;
};

/** Decimates a copy of \p input, posed by \p examples, through every target in one pass (the
 *  multiresolution hierarchy: each level continues from the previous one) with \p method, and snapshots
 *  the mesh as it passes each target. \p copied, if set, is called once the copy is made. */
std::vector<std::pair<Lod, Mesh>> build_chain(const Mesh& input, const std::vector<OpenMeshSkinned::Pose>& examples,
                                              const std::vector<size_t>& targets, const std::vector<double>& ratios,
                                              const Options& opt, const std::string& method, const std::string& label,
                                              const std::function<void()>& copied = {});
/** Releases what only an exported mesh needs (corner normals and UVs, face normals) from a mesh that is
 *  from now on only the reference surface the LODs are fitted to and measured against. */
void keep_as_reference_only(Mesh& mesh);

}  // namespace skinned_decimate
