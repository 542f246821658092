#pragma once
/** \file Refit.hh
 *  A final fit after decimation: every LOD vertex's rest position re-optimised against the original surface
 *  in all example poses at once. With the skins fixed, a posed vertex is an affine function of its rest
 *  position (morph offsets and linear blend skinning), so with the correspondences fixed the fit is one
 *  sparse linear least-squares problem; correspondences are then found again, a few rounds.
 *
 *  Residuals, in every example pose: each original vertex and triangle centroid to its closest point on the
 *  posed LOD (the LOD must cover the original; found again each round; weighed less along the LOD's surface
 *  than across it, RefitSettings::tangential_weight), and each LOD vertex to the point of
 *  the posed original nearest to it as decimated (the LOD must not leave the original; found once per
 *  pose, one search hierarchy per thread), plus a small pull toward the decimated positions (so that directions
 *  nothing constrains stay put). A round whose positions would turn a face by more than 90
 *  degrees in some pose is halved until none does.
 *
 *  Then, with RefitSettings::fit_weights, the skin: every LOD vertex's weights over its own and its
 *  neighbours' joints against the same residuals, the rest positions fixed (RefitWeights.hh); a face that
 *  would then fold in some pose keeps its corners' weights.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <vector>

namespace OpenMeshSkinned {

struct RefitSettings {
  int rounds = 3;
  double regularization = 1e-3;  ///< weight of the pull toward the decimated position, relative to one residual
  /// weight, in (0, 1], of the part of an original sample's residual along the LOD's surface, relative to the
  /// part across it (its square in the energy; 1: point to point; below, the fit slides along the surface as
  /// point-to-plane ICP does). RefitReport's residuals stay point to point.
  double tangential_weight = 0.7;
  size_t max_samples = 20000;  ///< original points (vertices, then centroids) per pose at most, evenly strided
  /// weight of the LOD's own surface drawn to the original, relative to the original's samples drawn to the LOD
  /// (the held-out measure is symmetric): points at fixed places on every LOD face, each pulled to where it
  /// lay on the posed original before the fit, weighted by area (0: only the LOD's vertices are). At most
  /// max_samples of them (fewer places a face), and none on a LOD of more than max_samples faces
  double face_weight = 1.0;
  int face_split = 3;  ///< those places: the centroids of each face split into face_split x face_split triangles
  /// Threads taking poses in turn (the answer does not depend on it; each holds one search hierarchy of the
  /// posed original, posed again for its next pose).
  int threads = 1;
  /// Larger LODs take each round's step from conjugate gradients instead of a sparse factorization, whose
  /// fill-in grows faster than the mesh (the step agrees to the solver's tolerance).
  size_t direct_max_vertices = 20000;
  /// After the positions, fit the skin weights too (RefitWeights.hh); false keeps every vertex's skin.
  bool fit_weights = true;
  /// joints per vertex at most when fitting the weights (1..Influences::kCapacity; 0: the most any LOD vertex
  /// has when the fit starts, so that a fit never adds influences a caller's cap took away)
  int max_influences = 0;
};

struct RefitReport {
  /// RMS of the residuals over the example poses, mesh units: before the first round and at the start of the
  /// last (the skin step's effect is not in it)
  double before = 0.0, after = 0.0;
  int rounds = 0;  ///< rounds that moved the vertices
};

/// Refits \p lod (a decimation of \p original, garbage-collected) in \p poses. UVs and morph offsets are
/// kept; rest positions move, and skin weights unless RefitSettings::fit_weights is false.
RefitReport refit_positions(SkinnedMesh& lod, const SkinnedMesh& original, const std::vector<Pose>& poses,
                            const RefitSettings& settings = {});

}  // namespace OpenMeshSkinned
