#pragma once
/** \file JointQuadrics.hh
 *  An edge's error with the poses summed out, once per solve.
 *
 *  With T_jk the 4x4 homogeneous transform of support joint k in pose j and Q_j the pose's summed quadric,
 *  a vertex v (homogeneous v~) with weights a summing to 1 has the quartic error
 *
 *      E(v, a) = sum_j (sum_k a_k T_jk v~)^T Q_j (sum_l a_l T_jl v~) = sum_kl a_k a_l v~^T G_kl v~,
 *      G_kl = sum_j T_jk^T Q_j T_jl.
 *
 *  Built once per edge (O(P m^2)), the m^2 matrices make every later step of the alternation independent
 *  of the pose count: the vertex step solves with C(a) = sum_kl a_k a_l G_kl, the weight step's Gram
 *  matrix is H_kl = v~^T G_kl v~, both O(m^2). They are kept per edge solve only: per vertex, for every
 *  pair of a skeleton's joints, they would take 16 doubles x J^2 (a 60-joint character: 460 KB a vertex).
 */

#include "OpenMeshSkinned/Solver/EdgeProblem.hh"

#include <Eigen/Core>

#include <array>

namespace OpenMeshSkinned {

class JointQuadrics {
public:
  static constexpr int kMax = EdgeProblem::kMaxSupport;

  /// Sums \p p's poses out (p.support joints, p.poses poses).
  void build(const EdgeProblem& p);

  int support() const { return m_; }

  /// C(a) = sum_kl a_k a_l G_kl: the quadric of a vertex with weights \p a, all poses summed.
  Eigen::Matrix4d blend(const WeightSolver::Vector& a) const;
  /// E(v, a) = v~^T C(a) v~ for a blended quadric \p c.
  static double energy(const Eigen::Matrix4d& c, const Eigen::Vector3d& v) {
    return std::max(0.0, v.homogeneous().dot(c * v.homogeneous()));
  }
  /// The weight Gram matrix at \p v: H_kl = v~^T G_kl v~.
  void weight_matrix(const Eigen::Vector3d& v, WeightSolver::Matrix& H) const;

private:
  int m_ = 0;
  // G_lk = G_kl^T: only k <= l is built and read.
  std::array<Eigen::Matrix4d, kMax * kMax> g_;
};

}  // namespace OpenMeshSkinned
