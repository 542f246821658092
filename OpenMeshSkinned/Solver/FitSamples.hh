#pragma once
/** \file FitSamples.hh
 *  The original's points that the final fit (Refit.hh) and the edge flips (EdgeFlipFit.hh) measure the LOD
 *  against: its vertices, then its triangles' centroids, evenly strided down to a budget, posed pose by pose;
 *  and how a residual of either is weighed.
 */

#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace OpenMeshSkinned {

/// \p mesh's faces as corner indices, in face order.
std::vector<std::array<int, 3>> mesh_triangles(const SkinnedMesh& mesh);

/// Sample numbers: i < n_vertices is vertex i (deleted ones skipped), i >= n_vertices triangle i - n_vertices;
/// every stride-th of them, so that at most about \p max_samples are kept.
std::vector<size_t> strided_samples(const SkinnedMesh& mesh, size_t n_triangles, size_t max_samples);

/// Where sample \p i lies with the vertices at \p points (\p n_vertices of them before the triangles).
inline Eigen::Vector3d sample_point(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<std::array<int, 3>>& triangles, size_t n_vertices, size_t i) {
  if (i < n_vertices) return points[i];
  const auto& t = triangles[i - n_vertices];
  return (points[t[0]] + points[t[1]] + points[t[2]]) / 3.0;
}

/// How a fit residual r is weighed, r^T W r: along \p normal (unit) in full and across it by \p tangential
/// (W = P^T P with P = n n^T + t (I - n n^T)), all of it times \p weight; a zero normal or a tangential
/// weight of 1 weighs it in full every way.
inline Eigen::Matrix3d residual_metric(const Eigen::Vector3d& normal, double tangential, double weight) {
  if (tangential == 1.0 || !(normal.squaredNorm() > 0.0)) return weight * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d nn = normal * normal.transpose();
  return weight * (nn + tangential * tangential * (Eigen::Matrix3d::Identity() - nn));
}

}  // namespace OpenMeshSkinned
