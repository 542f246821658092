// The collapse maths without a mesh: EdgeProblems built by hand from planes and joint transforms.
#include "one_joint_edge.hh"

#include <OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh>
#include <OpenMeshSkinned/Solver/TruncatedSolve.hh>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace OpenMeshSkinned;

namespace {

PoseQuadric plane(const Eigen::Vector3d& n, const Eigen::Vector3d& through, double area = 1.0) {
  const Eigen::Vector3d u = n.normalized();
  return PoseQuadric::plane(u, -u.dot(through), area);
}

// Three orthogonal planes through \p x: a quadric whose only zero is x.
PoseQuadric corner(const Eigen::Vector3d& x) {
  PoseQuadric q = plane(Eigen::Vector3d::UnitX(), x);
  q += plane(Eigen::Vector3d::UnitY(), x);
  q += plane(Eigen::Vector3d::UnitZ(), x);
  return q;
}

Affine3 translation(const Eigen::Vector3d& t) {
  Affine3 m = Affine3::Zero();
  m.leftCols<3>().setIdentity();
  m.col(3) = t;
  return m;
}

// Two joints; pose 0 the bind pose, pose 1 moves joint 1 by (0, 0, d). In pose 1 the corner sits at
// target + (0, 0, d w1): only the weight w1 on joint 1 puts the vertex on it in both poses.
EdgeProblem two_pose_corner(const Eigen::Vector3d& target, double w1, double d) {
  EdgeProblem p;
  Influences wa, wb;
  wa.push(0, 1.0);
  wb.push(1, 1.0);
  p.set_skins(wa, wb);
  p.resize(2);
  Pose bind = Pose::identity(2), moved = Pose::identity(2);
  moved.joint[1] = translation(Eigen::Vector3d(0, 0, d));
  p.set_pose(0, bind);
  p.set_pose(1, moved);
  p.quadric[0] = corner(target);
  p.quadric[1] = corner(target + Eigen::Vector3d(0, 0, d * w1));
  p.pa = target + Eigen::Vector3d(-0.3, 0.1, 0);
  p.pb = target + Eigen::Vector3d(0.3, -0.1, 0.05);
  return p;
}

}  // namespace

TEST(SkinnedQuadricSolve, SupportIsTheUnionOfTheEndpointsJointsAndStartsAtTheirAverage) {
  Influences wa, wb;
  wa.push(3, 0.75);
  wa.push(1, 0.25);
  wb.push(1, 0.5);
  wb.push(7, 0.5);
  EdgeProblem p;
  p.set_skins(wa, wb);
  ASSERT_EQ(p.support, 3);
  EXPECT_EQ(p.joint[0], 3);
  EXPECT_EQ(p.joint[1], 1);
  EXPECT_EQ(p.joint[2], 7);
  EXPECT_DOUBLE_EQ(p.start[0], 0.375);
  EXPECT_DOUBLE_EQ(p.start[1], 0.375);
  EXPECT_DOUBLE_EQ(p.start[2], 0.25);
}

TEST(SkinnedQuadricSolve, FindsThePositionAndWeightThatFitEveryPose) {
  const Eigen::Vector3d target(0.2, -0.4, 1.0);
  const EdgeProblem p = two_pose_corner(target, 0.3, 1.0);
  // The alternation halves the weight's distance to the optimum per step here: give it room.
  SolveSettings s;
  s.max_iterations = 40;
  WeightSolver ws;
  CollapseResult r;
  solve_collapse(p, s, ws, r);
  ASSERT_TRUE(r.valid);
  EXPECT_LT((r.position - target).norm(), 1e-4);
  EXPECT_NEAR(r.weights.weight_of(1), 0.3, 1e-4);
  EXPECT_NEAR(r.weights.sum(), 1.0, 1e-12);
  EXPECT_LT(r.error, 1e-6);
  EXPECT_NEAR(r.error,
              skinned_energy(p, r.position,
                             [&] {
                               WeightSolver::Vector a(2);
                               a << r.weights.weight_of(0), r.weights.weight_of(1);
                               return a;
                             }()),
              1e-12);
}

TEST(SkinnedQuadricSolve, ToleranceEndsTheAlternationWhenARoundStopsPaying) {
  // Here each round cuts the error to about a quarter: a tolerance of 0.9 asks for more than that and
  // stops after the second round; a tiny one runs on toward the optimum.
  const EdgeProblem p = two_pose_corner(Eigen::Vector3d(0.2, -0.4, 1.0), 0.3, 1.0);
  SolveSettings loose, tight;
  loose.max_iterations = tight.max_iterations = 40;
  loose.tolerance = 0.9;
  tight.tolerance = 1e-9;
  WeightSolver ws_loose, ws_tight;
  CollapseResult r_loose, r_tight;
  solve_collapse(p, loose, ws_loose, r_loose);
  solve_collapse(p, tight, ws_tight, r_tight);
  ASSERT_TRUE(r_loose.valid && r_tight.valid);
  EXPECT_EQ(ws_loose.stats().solves, 2u);
  EXPECT_GT(ws_tight.stats().solves, 5u);
  EXPECT_LT(r_tight.error, 0.01 * r_loose.error);
}

TEST(SkinnedQuadricSolve, EnergyIsTheSumOfThePosedQuadrics) {
  const EdgeProblem p = two_pose_corner(Eigen::Vector3d::Zero(), 0.5, 2.0);
  WeightSolver::Vector a(2);
  a << 1.0, 0.0;  // joint 0 only: the vertex does not move in pose 1, the corner moved by (0, 0, 1)
  const Eigen::Vector3d v(0.1, 0.2, 0.0);
  // pose 0: 0.01 + 0.04 + 0; pose 1: 0.01 + 0.04 + 1
  EXPECT_NEAR(skinned_energy(p, v, a), 0.05 + 1.05, 1e-12);
}

TEST(SkinnedQuadricSolve, CapKeepsTheSolutionWithinTheLimit) {
  EdgeProblem p = two_pose_corner(Eigen::Vector3d(0, 0, 1), 0.5, 1.0);
  SolveSettings s;
  s.max_influences = 1;
  WeightSolver ws;
  CollapseResult r;
  solve_collapse(p, s, ws, r);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.weights.size(), 1);
  EXPECT_DOUBLE_EQ(r.weights[0].weight, 1.0);
}

TEST(SkinnedQuadricSolve, FlatProblemsStayNearTheEdge) {
  // One plane: every point of it is optimal. The solve must not wander along it.
  const EdgeProblem p = omsk_test::one_joint_edge(plane(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()),
                                                  Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0));
  WeightSolver ws;
  CollapseResult r;
  solve_collapse(p, SolveSettings{}, ws, r);
  ASSERT_TRUE(r.valid);
  EXPECT_LE((r.position - 0.5 * (p.pa + p.pb)).norm(), 1e-9);
  EXPECT_LT(r.error, 1e-20);
}

TEST(SkinnedQuadricSolve, ReducingAVertexKeepsTheJointsThatMatter) {
  // A vertex at the corner, skinned to three joints; only joint 1's share moves it in pose 1, and the
  // plane there wants w1 = 0.6: the reduction to two joints must keep joint 1.
  EdgeProblem p = two_pose_corner(Eigen::Vector3d::Zero(), 0.6, 1.0);
  Influences w;
  w.push(0, 0.3);
  w.push(1, 0.6);
  w.push(2, 0.1);
  p.set_skins(w, w);
  p.resize(2);
  Pose bind = Pose::identity(3), moved = Pose::identity(3);
  moved.joint[1] = translation(Eigen::Vector3d(0, 0, 1.0));
  p.set_pose(0, bind);
  p.set_pose(1, moved);
  p.pa = p.pb = Eigen::Vector3d::Zero();
  SolveSettings s;
  s.max_influences = 2;
  WeightSolver ws;
  const Influences out = reduce_influences(p, s, ws);
  EXPECT_EQ(out.size(), 2);
  EXPECT_NEAR(out.weight_of(1), 0.6, 1e-3);
  EXPECT_NEAR(out.sum(), 1.0, 1e-12);
}

TEST(TruncatedSolve, LeavesUnconstrainedDirectionsAtTheReference) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  A(0, 0) = 2.0;  // only x is constrained: 2 x = 4
  Eigen::Vector3d x;
  bool full = true;
  ASSERT_TRUE(truncated_solve(A, Eigen::Vector3d(4, 0, 0), Eigen::Vector3d(9, 7, 5), x, &full));
  EXPECT_FALSE(full);
  EXPECT_NEAR(x.x(), 2.0, 1e-12);
  EXPECT_NEAR(x.y(), 7.0, 1e-12);
  EXPECT_NEAR(x.z(), 5.0, 1e-12);
  EXPECT_FALSE(truncated_solve(Eigen::Matrix3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), x));
  ASSERT_TRUE(
      truncated_solve(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3), Eigen::Vector3d::Zero(), x, &full));
  EXPECT_TRUE(full);
  EXPECT_NEAR((x - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, 1e-12);
}

TEST(TruncatedSolve, TheInverseShortcutAgreesWithThePseudoInverseEverywhere) {
  // Random rotations and eigenvalues from 1 down to 1e-5 of the largest, either side of the cutoff: the
  // answer (shortcut or eigen-decomposition) must be the truncated pseudo-inverse's.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-5.0, 0.0);
  int full_count = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Matrix3d R = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    const Eigen::Vector3d ev(1.0, std::pow(10.0, e(rng)), std::pow(10.0, e(rng)));
    const Eigen::Matrix3d A = 3.0 * R * ev.asDiagonal() * R.transpose();
    const Eigen::Vector3d rhs(u(rng), u(rng), u(rng)), ref(u(rng), u(rng), u(rng));
    Eigen::Vector3d x;
    bool full = false;
    ASSERT_TRUE(truncated_solve(A, rhs, ref, x, &full));
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    const Eigen::Vector3d r = R.transpose() * (rhs - A * ref);
    bool expect_full = true;
    for (int i = 0; i < 3; ++i) {
      if (3.0 * ev[i] > kPseudoInverseCutoff * 3.0)
        d[i] = r[i] / (3.0 * ev[i]);
      else
        expect_full = false;
    }
    const Eigen::Vector3d want = ref + R * d;
    EXPECT_EQ(full, expect_full) << "eigenvalues " << ev.transpose();
    EXPECT_LT((x - want).norm(), 1e-6 * (1.0 + want.norm())) << "eigenvalues " << ev.transpose();
    full_count += full;
  }
  EXPECT_GT(full_count, 100);
  EXPECT_LT(full_count, 1900);
}
