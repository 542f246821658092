// JointQuadrics: the poses summed out must give the same error, vertex step and weight matrix as the
// per-pose definitions, for any transforms, quadrics and weights.
#include <OpenMeshSkinned/Solver/JointQuadrics.hh>
#include <OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh>

#include <gtest/gtest.h>

#include <random>

using namespace OpenMeshSkinned;

namespace {

// A problem with m joints, P poses, random rigid-ish transforms with some scale, random quadrics.
EdgeProblem random_problem(int m, int poses, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EdgeProblem p;
  Influences wa, wb;
  for (int k = 0; k < m; ++k) (k % 2 ? wb : wa).push(k, 1.0);
  wa.normalize();
  wb.normalize();
  p.set_skins(wa, wb);
  p.resize(poses);
  for (int j = 0; j < poses; ++j) {
    Pose pose = Pose::identity(m);
    for (int k = 0; k < m; ++k) {
      pose.joint[k] = Affine3::Random();
      pose.joint[k].leftCols<3>() += Eigen::Matrix3d::Identity();
    }
    p.set_pose(j, pose);
    for (int f = 0; f < 4; ++f)
      p.quadric[j] += PoseQuadric::plane(Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized(), u(rng), 1.0 + u(rng));
  }
  return p;
}

WeightSolver::Vector random_weights(int m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  WeightSolver::Vector a(m);
  for (int k = 0; k < m; ++k) a[k] = k == 1 ? 0.0 : u(rng);  // one joint unused: the skipping path
  a /= a.sum();
  return a;
}

}  // namespace

TEST(JointQuadrics, EnergyEqualsTheSumOverPoses) {
  std::mt19937 rng(7);
  for (int m : {1, 2, 5, 8})
    for (int poses : {1, 3, 9}) {
      const EdgeProblem p = random_problem(m, poses, rng);
      JointQuadrics g;
      g.build(p);
      const WeightSolver::Vector a = random_weights(m, rng);
      const Eigen::Vector3d v = Eigen::Vector3d::Random();
      const double ref = skinned_energy(p, v, a);
      EXPECT_NEAR(JointQuadrics::energy(g.blend(a), v), ref, 1e-10 * (1.0 + ref)) << m << " joints, " << poses;
    }
}

TEST(JointQuadrics, SharedPosesGiveTheSameSolveAsCopiedOnes) {
  // The decimation's problems read the transforms from its poses (use_poses) instead of copying them.
  std::mt19937 rng(11);
  for (int m : {2, 5, 8}) {
    std::vector<Pose> poses;
    for (int j = 0; j < 4; ++j) {
      Pose pose = Pose::identity(m + 3);  // more joints than the support: indexed by skeleton joint
      for (auto& t : pose.joint) {
        t = Affine3::Random();
        t.leftCols<3>() += Eigen::Matrix3d::Identity();
      }
      poses.push_back(pose);
    }
    EdgeProblem copied = random_problem(m, 4, rng);
    for (int k = 0; k < m; ++k) copied.joint[k] += 3;  // the support is joints 3 .. m + 2
    for (int j = 0; j < 4; ++j) copied.set_pose(j, poses[j]);
    EdgeProblem shared = copied;
    shared.transform.clear();
    shared.use_poses(&poses);
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < m; ++k) EXPECT_EQ(shared.M(j, k), copied.M(j, k));
    CollapseResult a, b;
    WeightSolver wa, wb;
    solve_collapse(copied, SolveSettings{}, wa, a);
    solve_collapse(shared, SolveSettings{}, wb, b);
    ASSERT_TRUE(a.valid);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.weights, b.weights);
    EXPECT_EQ(a.error, b.error);
  }
}

TEST(JointQuadrics, WeightMatrixEqualsTheSumOverPoses) {
  std::mt19937 rng(11);
  const EdgeProblem p = random_problem(6, 5, rng);
  JointQuadrics g;
  g.build(p);
  const Eigen::Vector3d v(0.3, -0.7, 1.1);
  WeightSolver::Matrix H;
  g.weight_matrix(v, H);
  // H_kl = sum_j [M_jk v; 1]^T Q_j [M_jl v; 1]
  Eigen::MatrixXd ref = Eigen::MatrixXd::Zero(6, 6);
  for (int j = 0; j < p.poses; ++j)
    for (int k = 0; k < 6; ++k)
      for (int l = 0; l < 6; ++l)
        ref(k, l) += (p.M(j, k) * v.homogeneous())
                         .homogeneous()
                         .dot(p.quadric[j].matrix() * (p.M(j, l) * v.homogeneous()).homogeneous());
  EXPECT_LT((H - ref).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + ref.cwiseAbs().maxCoeff()));
  // a^T H a is the energy at v.
  const WeightSolver::Vector a = random_weights(6, rng);
  EXPECT_NEAR(a.dot(H * a), skinned_energy(p, v, a), 1e-9);
}

TEST(JointQuadrics, VertexStepMinimisesTheSumOverPoses) {
  std::mt19937 rng(3);
  const EdgeProblem p = random_problem(4, 6, rng);
  JointQuadrics g;
  g.build(p);
  const WeightSolver::Vector a = random_weights(4, rng);
  Eigen::Vector3d v;
  bool full = false;
  ASSERT_TRUE(skinned_vertex_step(g.blend(a), Eigen::Vector3d::Zero(), v, full));
  ASSERT_TRUE(full);
  // No step along any axis lowers the per-pose energy: v is its minimiser.
  const double e = skinned_energy(p, v, a);
  for (int d = 0; d < 3; ++d)
    for (double h : {-1e-3, 1e-3}) EXPECT_GE(skinned_energy(p, v + h * Eigen::Vector3d::Unit(d), a), e - 1e-12);
}
