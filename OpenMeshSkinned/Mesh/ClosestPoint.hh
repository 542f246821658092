#pragma once
/** \file ClosestPoint.hh
 *  The closest point of a triangle to a point, as barycentric coordinates: what attribute transfer onto a
 *  moved vertex (UVs, morph offsets) interpolates with.
 */

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {

/// Squared distance from \p q to triangle \p t, and the barycentric coordinates of the closest point.
/// A degenerate triangle is handled through its edges.
inline double closest_barycentric(const Eigen::Vector3d (&t)[3], const Eigen::Vector3d& q, Eigen::Vector3d& bary) {
  const Eigen::Vector3d e0 = t[1] - t[0], e1 = t[2] - t[0], d = q - t[0];
  const double a = e0.dot(e0), b = e0.dot(e1), c = e1.dot(e1), det = a * c - b * b;
  if (det > 1e-300 * (a * c + 1e-300)) {
    const double u = (c * e0.dot(d) - b * e1.dot(d)) / det, v = (a * e1.dot(d) - b * e0.dot(d)) / det;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) {
      bary = Eigen::Vector3d(1.0 - u - v, u, v);
      return (t[0] + u * e0 + v * e1 - q).squaredNorm();
    }
  }
  // Outside (or degenerate): the closest point lies on an edge.
  double best = HUGE_VAL;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d &x = t[i], &y = t[(i + 1) % 3];
    const double len2 = (y - x).squaredNorm();
    const double s = len2 > 0.0 ? std::clamp((q - x).dot(y - x) / len2, 0.0, 1.0) : 0.0;
    const double dist = (x + s * (y - x) - q).squaredNorm();
    if (dist < best) {
      best = dist;
      bary.setZero();
      bary[i] = 1.0 - s;
      bary[(i + 1) % 3] = s;
    }
  }
  return best;
}

}  // namespace OpenMeshSkinned
