#pragma once
/** \file EdgeProblem.hh
 *  One edge as the collapse kernel (SkinnedQuadricSolve.hh) and the pose-summed quadrics (JointQuadrics.hh)
 *  see it: the endpoints' summed per-pose quadrics, their joints' transforms, positions and skins.
 */

#include "OpenMeshSkinned/Skin/Influences.hh"
#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/WeightSolver.hh"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace OpenMeshSkinned {

/** One edge (or one vertex, with a == b) as the kernel sees it. Reused between solves: its vectors keep
 *  their capacity, so filling a problem does not allocate once they have grown to the pose count. */
struct EdgeProblem {
  static constexpr int kMaxSupport = 2 * Influences::kCapacity;
  static_assert(kMaxSupport <= WeightSolver::kMaxJoints, "the weight solve must hold both endpoints' joints");

  int poses = 0;                         ///< P
  int support = 0;                       ///< m, the joints the merged vertex may use
  std::array<int, kMaxSupport> joint{};  ///< their skeleton indices
  std::vector<PoseQuadric> quadric;      ///< per pose: the endpoints' quadrics, summed
  std::vector<Affine3> transform;        ///< pose j, support joint k at [j * kMaxSupport + k] (set_pose's copies)
  Eigen::Vector3d pa = Eigen::Vector3d::Zero(), pb = Eigen::Vector3d::Zero();  ///< endpoints' rest positions
  WeightSolver::Vector start;  ///< start weights on the support (the endpoints' average)
  /// The endpoints' rest-pose normal quadrics (NormalQuadric.hh), weighted, summed; zero when not priced.
  PoseQuadric attribute;

  /// Sets the support to the union of \p wa's and \p wb's joints, and the start to their average weights.
  void set_skins(const Influences& wa, const Influences& wb);
  /// Sizes the per-pose arrays for \p n poses (the transforms' only without use_poses()).
  void resize(int n);
  /// Copies the support joints' transforms of pose \p j from \p pose.
  void set_pose(int j, const Pose& pose);
  /** Reads every pose's transforms from \p poses (one per pose, indexed by skeleton joint) instead of
   *  copies: \p poses must outlive the problem's solves. The decimation's poses do not change while it
   *  runs, and copying them was a tenth of filling a problem (null: back to the copies). */
  void use_poses(const std::vector<Pose>* poses) { shared_poses = poses; }

  const Affine3& M(int j, int k) const {
    return shared_poses ? (*shared_poses)[j].joint[joint[k]] : transform[j * kMaxSupport + k];
  }
  const std::vector<Pose>* shared_poses = nullptr;
};

}  // namespace OpenMeshSkinned
