#pragma once
/** \file TruncatedSolve.hh
 *  Lindstrom's truncated pseudo-inverse for the 3x3 systems of quadric placement.
 */

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace OpenMeshSkinned {

/// Eigenvalues below this fraction of the largest count as directions the quadric does not constrain.
inline constexpr double kPseudoInverseCutoff = 1e-3;

/** Solves A x = rhs for a symmetric positive semi-definite \p A, leaving the directions \p A barely
 *  constrains (along a straight crease, across a flat patch) at \p ref: solving those exactly would fling
 *  the point far along a valley of near-zero error. Returns false when nothing is constrained (A = 0);
 *  \p full_rank, when given, tells whether every direction was. */
inline bool truncated_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& rhs, const Eigen::Vector3d& ref,
                            Eigen::Vector3d& x, bool* full_rank = nullptr) {
  // With eigenvalues l1 <= l2 <= l3 of a PSD matrix, l3 <= trace and l1 = det / (l2 l3) >= det / trace^2:
  // det > cutoff * trace^3 proves every direction constrained, and the pseudo-inverse is the inverse
  // (most quadrics after a few collapses; the eigen-decomposition was a tenth of a decimation).
  const double tr = A.trace(), det = A.determinant();
  if (tr > 0.0 && det > kPseudoInverseCutoff * tr * tr * tr) {
    if (full_rank) *full_rank = true;
    x = A.inverse() * rhs;
    return true;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(A);  // closed form for 3x3, several times faster than the iterative solver
  const Eigen::Vector3d ev = es.eigenvalues();
  if (!(ev[2] > 0.0)) return false;
  const Eigen::Vector3d r = es.eigenvectors().transpose() * (rhs - A * ref);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  bool all = true;
  for (int i = 0; i < 3; ++i) {
    if (ev[i] > kPseudoInverseCutoff * ev[2])
      d[i] = r[i] / ev[i];
    else
      all = false;
  }
  if (full_rank) *full_rank = all;
  x = ref + es.eigenvectors() * d;
  return true;
}

}  // namespace OpenMeshSkinned
