#pragma once
// The held-out error of LODs: each LOD against the original, both posed in the same frames, as Metro-style
// surface distances in percent of the original's rest-pose bounding-box diagonal.

#include <OpenMeshSkinned/Lod/LodProgress.hh>
#include <OpenMeshSkinned/Skin/Skeleton.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <vector>

namespace OpenMeshSkinned {

struct HeldOutError {
  double rms = 0.0;                 ///< mean over the frames of each frame's symmetric RMS distance, %
  double hausdorff = 0.0;           ///< max over the frames of the symmetric Hausdorff distance, %
  std::vector<float> vertex_error;  ///< per LOD vertex, its worst over the frames, % (when asked for)
};

struct EvaluateOptions {
  int threads = 0;                ///< frames measured on this many threads (0: the hardware's)
  bool per_vertex_error = false;  ///< fill HeldOutError::vertex_error
  size_t samples = 20000;         ///< area samples per surface and frame (plus every vertex)
  /// at most this many of a surface's vertices count toward the RMS, evenly spread (0: all); every vertex
  /// still counts toward the Hausdorff distance (surface_distance's counted_vertices)
  size_t counted_vertices = 20000;
};

/** Each of \p lods against \p original in \p frames (poses of the original's skeleton).
 *  \p lod_frames[i], when not empty, are LOD i's own poses of the same frames (its skeleton or clips were
 *  reduced). The numbers do not depend on the thread count. Throws LodCancelled when \p callbacks cancels. */
std::vector<HeldOutError> evaluate_lods(const SkinnedMesh& original, const std::vector<const SkinnedMesh*>& lods,
                                        const std::vector<Pose>& frames,
                                        const std::vector<std::vector<Pose>>& lod_frames = {},
                                        const EvaluateOptions& options = {}, const LodCallbacks& callbacks = {});

/// One LOD, posed as the original in \p frames.
HeldOutError evaluate(const SkinnedMesh& original, const SkinnedMesh& lod, const std::vector<Pose>& frames,
                      const EvaluateOptions& options = {});

}  // namespace OpenMeshSkinned
