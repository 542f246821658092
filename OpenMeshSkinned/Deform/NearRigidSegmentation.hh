#pragma once
/** \file NearRigidSegmentation.hh
 *  Lee et al., "Segmenting a deforming mesh into near-rigid components": faces are split into parts
 *  that each move (nearly) by one affine map over the whole animation, with the cuts in the regions that
 *  bend.
 *
 *  What is taken from the paper:
 *  - the dual graph (faces, edges between neighbours) with the combined distance of eq. 5,
 *    Dis = delta Geod / avg(Geod) + (1 - delta) D / avg(D), D being the deformation distance of eq. 4;
 *  - the feature faces (3.2): set A = faces with a neighbour farther than epsilon, B = the rest; repeatedly
 *    the face of B farthest from A is a feature face, its influence region R is where the harmonic field
 *    (1 at the feature face, 0 on A) is at least 0.01, R joins an existing part when the average
 *    deformation gradients of the two are within gamma (squared Frobenius norm of their difference; the
 *    paper does not say over which frames: here its mean over the frames, as the worst frame over a long
 *    animation keeps every pair apart) and otherwise starts a new part, and R moves to A; until R's area
 *    is under min_region_area of the whole. Pieces of the mesh that no face of A reaches (a separate rigid
 *    accessory) are each a region of their own first, whatever their size;
 *  - the clustering of 3.3: every face goes to the part of its nearest feature face (eq. 6, shortest paths
 *    on the dual graph), then, round by round until no face moves, to the part i minimising min(distance
 *    to i's nearest feature face, average distance to i's faces) (eq. 7); a part that falls apart into
 *    disconnected pieces (Fig. 4) is split: pieces holding feature faces become parts of their own, pieces
 *    without one join the neighbour they share most edges with.
 *
 *  Changed, and why: eq. 7's average over all of a part's faces needs all-pairs shortest paths (the
 *  paper's own memory limit: F^2 distances); it is taken over up to 24 faces spread through the part.
 *  The boundaries are then smoothed (3.4) by a minimum cut through a band around each (Boykov-Kolmogorov,
 *  Boost); the extracted eq. 8 puts D/avg(D) itself into the capacity, which would make the cut avoid the
 *  bending regions the prose says it follows, so the deformation term is Katz & Tal's 1 / (1 + D/avg(D))
 *  (Lee's reference [15]).
 */

#include "OpenMeshSkinned/Deform/DeformationAnalysis.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <vector>

namespace OpenMeshSkinned {

struct SegmentationSettings {
  double delta = 0.15;            ///< eq. 5: share of the geodesic term (the paper: 0.1 to 0.2)
  double epsilon = 0.5;           ///< set A: a face with a neighbour farther than this (the paper: 0.3 to 0.8)
  double gamma = 0.4;             ///< merge threshold on average gradients (the paper: 0.4 to 1.6)
  double min_region_area = 0.01;  ///< stop when an influence region has less of the total area
  double alpha = 0.1;             ///< eq. 8: share of the deformation term in the cut's capacity (the paper: < 0.1)
  int smoothing_hops = 3;         ///< 3.4: faces this many steps from a boundary may change side (0: no smoothing)
};

struct Segmentation {
  std::vector<int> part;  ///< by face index, 0 .. parts - 1
  int parts = 0;
  std::vector<int> feature_faces;  ///< face indices
};

/// Segments \p mesh over \p frames (positions by vertex index), \p ref being the reference frame.
Segmentation segment_near_rigid(const SkinnedMesh& mesh, const FramePoints& ref, const std::vector<FramePoints>& frames,
                                const SegmentationSettings& s = {});

}  // namespace OpenMeshSkinned
