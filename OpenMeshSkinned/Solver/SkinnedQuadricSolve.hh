#pragma once
/** \file SkinnedQuadricSolve.hh
 *  The maths of one collapse, without a mesh: Landreneau & Schaefer's quartic error (eq. 3)
 *
 *      E(v, a) = sum_poses (sum_k a_k M_k v)^T Q (sum_k a_k M_k v)
 *
 *  minimised over the rest position v and the weights a (support: the endpoints' joints) by alternating
 *  the 3x3 vertex solve (3.1) and the constrained weight solve (3.2, WeightSolver), starting from the
 *  endpoints' average weights, until the error stops falling. The poses are summed out once per edge
 *  (JointQuadrics.hh), so the alternation's steps cost the same whatever the pose count.
 *
 *  Everything the solve reads is in the EdgeProblem it is given; the mesh-facing solver (CollapseSolverT)
 *  only fills problems and applies results. The same kernel reduces a single vertex to the cap.
 */

#include "OpenMeshSkinned/Skin/Influences.hh"
#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/WeightSolver.hh"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace OpenMeshSkinned {

/// The solver's answer for one edge.
struct CollapseResult {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< rest-pose position of the merged vertex
  Influences weights;                                  ///< its skin, within the cap
  double error = 0.0;                                  ///< quartic error E(position, weights), >= 0
  /// The area the endpoints' quadrics stand for (the trace of their summed plane matrices, averaged over
  /// the poses): error / area is a mean squared distance (ModSkinnedQuadricT::set_error_per_area).
  double area = 0.0;
  bool valid = false;  ///< false when the solve produced nothing finite
};

/// The settings the kernel reads (the rest of SolverSettings is the mesh-facing solver's).
struct SolveSettings {
  int max_influences = Influences::kCapacity;
  // Greedy kept the posed surface closer on every real character and cap measured (bench/README.md,
  // "omsk-bench: the papers' workloads", cap-strategy), by far on the FBX character, whose raw weights use
  // up to 8 bones. (TopN looked better before the weight solve's badly scaled KKT systems were fixed.)
  CapStrategy strategy = CapStrategy::Greedy;
  int max_iterations = 8;
  // A round that lowers the error by less than this fraction ends the alternation. 1e-2 needs far fewer
  // weight solves than 1e-4, with the peer benchmark's held-out errors unchanged to within its noise
  // (bench/README.md, "Defaults chosen by measurement").
  double tolerance = 1e-2;
};

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

/// E(v, a) of \p p by its definition, pose by pose (the solve itself sums the poses out: JointQuadrics.hh).
double skinned_energy(const EdgeProblem& p, const Eigen::Vector3d& v, const WeightSolver::Vector& a);

/** The vertex step at fixed weights: the minimiser of v~^T C v~ for the blended quadric \p c (all poses
 *  summed, JointQuadrics::blend), solved by the truncated pseudo-inverse around \p ref. False when nothing
 *  is constrained; \p full_rank tells whether every direction was. */
bool skinned_vertex_step(const Eigen::Matrix4d& c, const Eigen::Vector3d& ref, Eigen::Vector3d& v, bool& full_rank);

/// The optimal merged vertex for \p p within \p s's cap.
void solve_collapse(const EdgeProblem& p, const SolveSettings& s, WeightSolver& weights, CollapseResult& out);

/** A vertex with more than s.max_influences joints, reduced by the weight solve on its own quadrics at
 *  its own position (p.pa; the start holds its weights), not by truncation. */
Influences reduce_influences(const EdgeProblem& p, const SolveSettings& s, WeightSolver& weights);

}  // namespace OpenMeshSkinned
