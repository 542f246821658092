#pragma once
/** \file FitSamples.hh
 *  The original's points that the final fit (Refit.hh) and the edge flips (EdgeFlipFit.hh) measure the LOD
 *  against: its vertices, then its triangles' centroids, evenly strided down to a budget, posed pose by pose.
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

}  // namespace OpenMeshSkinned
