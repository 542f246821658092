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
#include "OpenMeshSkinned/Solver/EdgeProblem.hh"
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
  /// Weight of the rest-pose normal quadrics (NormalQuadric.hh) against the posed geometry; 0: geometry only.
  double normal_weight = 0.0;
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
