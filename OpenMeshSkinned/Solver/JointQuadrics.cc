#include "OpenMeshSkinned/Solver/JointQuadrics.hh"

namespace OpenMeshSkinned {

void JointQuadrics::build(const EdgeProblem& p) {
  m_ = p.support;
  for (int k = 0; k < m_; ++k)
    for (int l = k; l < m_; ++l) g_[k * kMax + l].setZero();
  std::array<Eigen::Matrix4d, kMax> qt;  // Q_j T_jl for the pose at hand
  for (int j = 0; j < p.poses; ++j) {
    const Eigen::Matrix4d q = p.quadric[j].matrix();
    // T = [M; 0 0 0 1]: Q T = Q.leftCols(3) M + last column of Q times the last row of T.
    for (int l = 0; l < m_; ++l) {
      const Affine3& M = p.M(j, l);
      qt[l].noalias() = q.leftCols<3>() * M;
      qt[l].col(3) += q.col(3);
    }
    for (int k = 0; k < m_; ++k) {
      const Affine3& M = p.M(j, k);
      for (int l = k; l < m_; ++l) {
        Eigen::Matrix4d& g = g_[k * kMax + l];
        g.topRows<3>().noalias() += M.transpose().topRows<3>() * qt[l].topRows<3>();
        g.row(3).noalias() += M.col(3).transpose() * qt[l].topRows<3>() + qt[l].row(3);
      }
    }
  }
}

Eigen::Matrix4d JointQuadrics::blend(const WeightSolver::Vector& a) const {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  for (int k = 0; k < m_; ++k) {
    if (a[k] == 0.0) continue;
    c += (a[k] * a[k]) * g_[k * kMax + k];
    for (int l = k + 1; l < m_; ++l)
      if (a[l] != 0.0) {
        const Eigen::Matrix4d& g = g_[k * kMax + l];
        c += (a[k] * a[l]) * (g + g.transpose());
      }
  }
  return c;
}

void JointQuadrics::weight_matrix(const Eigen::Vector3d& v, WeightSolver::Matrix& H) const {
  H.resize(m_, m_);
  const Eigen::Vector4d x = v.homogeneous();
  for (int k = 0; k < m_; ++k)
    for (int l = k; l < m_; ++l) H(k, l) = H(l, k) = x.dot(g_[k * kMax + l] * x);
}

}  // namespace OpenMeshSkinned
