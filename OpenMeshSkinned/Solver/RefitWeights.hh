#pragma once
/** \file RefitWeights.hh
 *  The final fit's skin step: with the LOD's rest positions fixed, a posed vertex is linear in its skin
 *  weights, so the fit's residuals (refit_positions, Refit.hh) are a small constrained least-squares
 *  problem per vertex in its weights: the weight solve of the decimation (WeightSolver, Landreneau &
 *  Schaefer 3.2: weights >= 0 summing to one, at most a cap of them) on the residuals that touch the vertex,
 *  its neighbours' weights held at their latest values (one Gauss-Seidel sweep).
 *
 *  The decimation solved a merged vertex's weights where it stood before the fit moved it, and only from
 *  its two endpoints' joints; here the candidates are its own joints and its one-ring's, so a vertex left
 *  on one bone next to a joint can blend into the next one.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace OpenMeshSkinned {

/// One residual of the fit: a point of the posed LOD (\p corners vertices, barycentric \p bary; one corner
/// for a vertex) to \p target in pose \p pose, measured along \p normal in full and across it with the
/// tangential weight (a zero normal: in full every way), its square weighted by \p weight.
struct WeightResidual {
  std::array<int, 3> v{{-1, -1, -1}};
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double weight = 1.0;
  int corners = 1;
  int pose = 0;
};

struct WeightRefitSettings {
  /// joints per vertex at most (the LOD's cap); a vertex that has more keeps its count
  int max_influences = 4;
  double tangential_weight = 1.0;  ///< as RefitSettings::tangential_weight
  /// pull toward the vertex's current weights, relative to the mean diagonal of its problem
  /// (WeightSolver::set_regularization)
  double regularization = 1e-3;
};

/// One sweep over \p lod's vertices in index order, each solved against the \p residuals that touch it in
/// \p poses. Vertices with a single candidate joint keep it. Returns how many vertices' weights changed.
size_t refit_weights(SkinnedMesh& lod, const std::vector<Pose>& poses, const std::vector<WeightResidual>& residuals,
                     const WeightRefitSettings& settings = {});

}  // namespace OpenMeshSkinned
