#pragma once
/** \file ModPoseIndependentQuadricT.hh */

#include "OpenMeshSkinned/Decimater/Baselines/RestSpaceQuadricModuleT.hh"

#include <boost/math/special_functions/erf.hpp>

#include <algorithm>
#include <cfloat>
#include <map>
#include <random>

namespace OpenMeshSkinned {

/// How one joint moves, for ModPoseIndependentQuadricT: a rotation about \p axis (joint-local) by an
/// angle drawn from a box [lo, hi] or a Gaussian around a preferred angle. Angles in degrees.
struct JointDistribution {
  enum Kind { Box, Gaussian } kind = Box;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  double lo = 0.0, hi = 0.0;  ///< Box
  double preferred = 0.0;     ///< Gaussian mean
  double stiffness = 1.0;     ///< Gaussian: density ~ exp(-stiffness (angle - preferred)^2 / 2), angle in radians
};

/** Priority module: DeCoro & Rusinkiewicz's pose-independent quadric (I3D 2005).
 *
 *  Each vertex's quadric is the expectation, over the poses the character may take, of its posed quadric
 *  pulled back to the rest pose through the vertex's own skinning transform:
 *  Q_v = sum_P rho(P) M_v(P)^T Q_v(P) M_v(P) / sum_P rho(P) (paper eq. 10-13). The poses are drawn by
 *  stratified Monte Carlo: from per-joint distributions when set (Latin-hypercube strata per joint,
 *  jittered), otherwise from the character's own animation clips (jittered strata over the clips laid
 *  end to end: their empirical distribution). With neither, the bind pose alone (the rest-pose quadric).
 *  The samples are drawn from rho itself, so each counts once.
 *
 *  The merged vertex sits at the quadric's optimum; its skin follows DeCoro's distance interpolation
 *  t = d0 / (d0 + d1) (selectable, see WeightRules.hh). Units: squared length times area.
 *
 *  Simplification: the paper refines strata recursively where the sampled error varies most; here every
 *  stratum gets one sample. With the default 64 samples that is the same estimator at a fixed budget.
 */
template <typename MeshT>
class ModPoseIndependentQuadricT : public RestSpaceQuadricModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModPoseIndependentQuadricT, MeshT, PoseIndependentQuadric);

  explicit ModPoseIndependentQuadricT(MeshT& mesh) : RestSpaceQuadricModuleT<MeshT>(mesh) {}

  /// Monte Carlo samples (default 64). Set before initialize().
  void set_samples(int n) { samples_ = std::max(1, n); }
  int samples() const { return samples_; }
  void set_seed(uint64_t s) { seed_ = s; }
  /// The distribution of one joint; joints without one keep their rest transform (or follow the clips,
  /// when no joint has a distribution).
  void set_joint_distribution(int joint, const JointDistribution& d) { joint_dist_[joint] = d; }
  void clear_joint_distributions() { joint_dist_.clear(); }
  /// Poses drawn by the last initialize().
  size_t samples_used() const { return samples_used_; }

protected:
  void build_quadrics(std::vector<PoseQuadric>& quadrics) override {
    MeshT& mesh = Base::mesh();
    const auto h_inf = this->influences();
    const std::vector<Pose> poses = sample_poses();
    samples_used_ = poses.size();
    std::vector<Eigen::Vector3d> posed(mesh.n_vertices());
    std::vector<PoseQuadric> q(mesh.n_vertices());
    for (const Pose& pose : poses) {
      for (auto v : mesh.vertices())
        posed[v.idx()] = skin_point(to_eigen(mesh.point(v)), mesh.property(h_inf, v), pose);
      std::fill(q.begin(), q.end(), PoseQuadric{});
      accumulate_quadrics(
          mesh, 1, [&](typename MeshT::VertexHandle v, int) { return posed[v.idx()]; },
          [&](typename MeshT::VertexHandle v, int) -> PoseQuadric& { return q[v.idx()]; });
      // Pull back: x -> M_v x maps the rest position to the posed one, so (M x)^T Q (M x) = x^T (M^T Q M) x.
      for (auto v : mesh.vertices()) {
        Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
        M.topRows<3>() = blend(mesh.property(h_inf, v), pose);
        const Eigen::Matrix4d R = M.transpose() * q[v.idx()].matrix() * M / double(poses.size());
        const double add[10] = {R(0, 0), R(0, 1), R(0, 2), R(0, 3), R(1, 1),
                                R(1, 2), R(1, 3), R(2, 2), R(2, 3), R(3, 3)};
        for (int i = 0; i < 10; ++i) quadrics[v.idx()].q[i] += add[i];
      }
    }
  }

private:
  std::vector<Pose> sample_poses() {
    const MeshT& mesh = Base::mesh();
    const Skeleton& skel = skeleton(mesh);
    const auto& cl = clips(mesh);
    std::mt19937_64 rng(seed_);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Pose> out;
    if (!joint_dist_.empty()) {
      // Latin hypercube: each joint's angle gets one jittered sample in each of n strata of its
      // distribution's quantiles, the strata shuffled independently per joint.
      const int n = samples_;
      std::map<int, std::vector<double>> angle;
      for (const auto& [j, d] : joint_dist_) {
        std::vector<double> a(n);
        for (int i = 0; i < n; ++i) {
          const double qnt = (i + u(rng)) / n;
          if (d.kind == JointDistribution::Box) {
            a[i] = d.lo + qnt * (d.hi - d.lo);
          } else {
            const double sigma = 1.0 / std::sqrt(std::max(d.stiffness, 1e-12)) * 180.0 / M_PI;
            a[i] = d.preferred + sigma * std::sqrt(2.0) *
                                     boost::math::erf_inv(std::clamp(2.0 * qnt - 1.0, -1.0 + 1e-12, 1.0 - 1e-12));
          }
        }
        std::shuffle(a.begin(), a.end(), rng);
        angle[j] = a;
      }
      for (int i = 0; i < n; ++i) {
        std::vector<Eigen::Matrix4d> locals(skel.joints.size());
        for (size_t j = 0; j < skel.joints.size(); ++j) locals[j] = skel.joints[j].rest_local;
        for (const auto& [j, d] : joint_dist_) {
          if (j < 0 || j >= skel.size()) continue;
          Eigen::Matrix4d r = Eigen::Matrix4d::Identity();
          r.topLeftCorner<3, 3>() =
              Eigen::AngleAxisd(angle[j][i] * M_PI / 180.0, d.axis.normalized()).toRotationMatrix();
          locals[j] = skel.joints[j].rest_local * r;
        }
        Pose p;
        p.joint = skel.skinning(locals);
        out.push_back(std::move(p));
      }
      return out;
    }
    double total = 0.0;
    for (const Clip& c : cl) total += c.duration;
    if (cl.empty()) return {Pose::identity(skel.size())};
    // Empirical distribution of the clips: one jittered time in each of n strata of the clips end to end.
    for (int i = 0; i < samples_; ++i) {
      double s = (i + u(rng)) / samples_ * total;
      size_t c = 0;
      while (c + 1 < cl.size() && s >= cl[c].duration) s -= cl[c++].duration;
      out.push_back(sample_pose(skel, cl[c], std::min(s, cl[c].duration)));
    }
    return out;
  }

  std::map<int, JointDistribution> joint_dist_;
  int samples_ = 64;
  uint64_t seed_ = 1;
  size_t samples_used_ = 0;
};

}  // namespace OpenMeshSkinned
