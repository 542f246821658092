#pragma once
/** \file EdgeFlipFit.hh
 *  Edge flips after decimation, judged against the original in every example pose (Hoppe et al. 1993's
 *  edge swap, posed). A collapse sequence leaves the diagonal of many quads where the last collapse put it,
 *  not where the surface needs it: across a curved patch the other diagonal can lie closer to the original.
 *
 *  An interior edge ab with faces abc and bad becomes cd when, summed over the poses, the squared distance
 *  of the two faces' area samples to the posed original, plus that of the original's samples that lie
 *  nearest to them to the two faces, falls. A flip is refused where it would change what the surface
 *  shows or how it bends: across an attribute seam (at a and at b both faces' corners must carry the same UVs
 *  and colours, and normals no hard edge apart, Seams.hh), between materials, where cd is already an edge,
 *  onto a degenerate face, where the two new faces fold against each other or turn from the old ones by
 *  90 degrees or more in some pose, or where the normals the exporter would recompute from the faces turn,
 *  over the quad and summed over the poses, further from the original's smooth normals at the nearest
 *  points (a flip that fits the shape better can still shade worse). Flips whose faces touch are taken best first, one
 * per face per sweep; sweeps repeat while they flip, each after the first only around the last one's flips.
 *  Most edges are settled by a screen of a few poses (FlipFitSettings::screen_poses); the rest are summed over
 *  every pose, on the original's samples that lay near them in the screen.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <vector>

namespace OpenMeshSkinned {

struct FlipFitSettings {
  int sweeps = 3;
  size_t max_samples = 20000;  ///< original points (vertices, then centroids) per pose at most, evenly strided
  double min_gain = 1e-3;      ///< relative fall of the quad's error a flip must bring
  /// and its absolute fall: this RMS distance, in units of the original's bounding-box diagonal, over the quad
  double tolerance = 1e-5;
  int threads = 1;  ///< threads taking poses in turn (the answer does not depend on it)
  /// Poses, spread over the list, that screen the edges first: one whose flip folds in one of them, or at least
  /// doubles the quad's error summed over them, is not judged in the others (0 or at least the pose count:
  /// every edge in every pose, on every sample)
  int screen_poses = 4;
};

struct FlipFitReport {
  int flips = 0;                     ///< edges flipped, all sweeps
  int sweeps = 0;                    ///< sweeps that flipped
  double before = 0.0, after = 0.0;  ///< the flipped quads' error, summed over poses, before and after
};

/// Flips edges of \p lod (a decimation of \p original, garbage-collected) in \p poses. Vertices, skins,
/// corner attributes and materials are kept; only which vertices the faces join changes.
FlipFitReport flip_edges_to_fit(SkinnedMesh& lod, const SkinnedMesh& original, const std::vector<Pose>& poses,
                                const FlipFitSettings& settings = {});

}  // namespace OpenMeshSkinned
