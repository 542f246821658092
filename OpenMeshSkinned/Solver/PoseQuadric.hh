#pragma once
/** \file PoseQuadric.hh
 *  A Garland-Heckbert quadric as 10 doubles (the upper triangle of a symmetric 4x4), stored flat so a
 *  vertex's per-pose quadrics sit next to each other in memory.
 */

#include <Eigen/Core>

namespace OpenMeshSkinned {

struct PoseQuadric {
  // a b c d / e f g / h i / j  -> [[a b c d] [b e f g] [c f h i] [d g i j]]
  double q[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};

  /// area * (n.x + d)^2 for the plane n.x + d = 0 (n unit).
  static PoseQuadric plane(const Eigen::Vector3d& n, double d, double area) {
    PoseQuadric p;
    const double a = n.x(), b = n.y(), c = n.z();
    p.q[0] = area * a * a;
    p.q[1] = area * a * b;
    p.q[2] = area * a * c;
    p.q[3] = area * a * d;
    p.q[4] = area * b * b;
    p.q[5] = area * b * c;
    p.q[6] = area * b * d;
    p.q[7] = area * c * c;
    p.q[8] = area * c * d;
    p.q[9] = area * d * d;
    return p;
  }

  PoseQuadric& operator+=(const PoseQuadric& o) {
    for (int i = 0; i < 10; ++i) q[i] += o.q[i];
    return *this;
  }

  Eigen::Matrix3d A() const {
    Eigen::Matrix3d m;
    m << q[0], q[1], q[2], q[1], q[4], q[5], q[2], q[5], q[7];
    return m;
  }
  Eigen::Vector3d b() const { return Eigen::Vector3d(q[3], q[6], q[8]); }
  double c() const { return q[9]; }

  Eigen::Matrix4d matrix() const {
    Eigen::Matrix4d m;
    m << q[0], q[1], q[2], q[3], q[1], q[4], q[5], q[6], q[2], q[5], q[7], q[8], q[3], q[6], q[8], q[9];
    return m;
  }

  /// x^T Q x for the point x (homogeneous coordinate 1).
  double operator()(const Eigen::Vector3d& x) const { return x.dot(A() * x) + 2.0 * b().dot(x) + c(); }
};

}  // namespace OpenMeshSkinned
