#pragma once
/** \file SkeletonLodT.hh
 *  Skeleton LoD on a skinned mesh: the reduced skeleton and baked clips of reduce_skeleton(), the removed
 *  joints' weights handed to the joint that takes over their motion (the nearest kept ancestor), then,
 *  beyond the paper, every affected vertex's skin re-solved against the example poses with the reduced
 *  joint set (the skinned quadric's weight solve at the vertex's position, within the cap), not only
 *  reassigned.
 */

#include "OpenMeshSkinned/Skin/SkeletonLod.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"
#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

namespace OpenMeshSkinned {

namespace detail {

/** Beyond the paper's energy order: a joint costs what handing its weights to the heir moves the
 *  vertices, sum over vertices of weight x the largest displacement over the example poses of \p cache. */
template <typename Mesh>
JointRemovalCost displacement_cost(const Mesh& mesh, const PoseCacheT<Mesh>& cache, int n_joints) {
  const auto h = influences_handle(mesh);
  std::vector<std::vector<std::pair<int, double>>> bound(n_joints);  // joint -> (vertex, weight)
  for (auto vh : mesh.vertices())
    for (const JointWeight& jw : mesh.property(h, vh)) bound[jw.joint].push_back({vh.idx(), jw.weight});
  return [&mesh, &cache, bound = std::move(bound)](int j, int heir) {
    double c = 0.0;
    for (const auto& [v, w] : bound[j]) {
      const Eigen::Vector4d p = to_eigen(mesh.point(typename Mesh::VertexHandle(v))).homogeneous();
      double worst = 0.0;
      for (int k = 0; k < cache.n_poses(); ++k) {
        const Affine3& a = cache.pose(k).joint[j];
        const Affine3 b = heir >= 0 ? cache.pose(k).joint[heir] : Affine3(Affine3::Identity());
        worst = std::max(worst, ((a - b) * p).norm());
      }
      c += w * worst;
    }
    return c;
  };
}

/// A removed joint's kept descendants just below it, per removed joint.
inline std::vector<std::vector<int>> kept_successors(const Skeleton& original, const SkeletonReduction& red) {
  std::vector<std::vector<int>> successors(original.size());
  for (int k = 0; k < original.size(); ++k) {
    if (red.new_index[k] < 0) continue;
    for (int p = original.joints[k].parent; p >= 0 && red.new_index[p] < 0; p = original.joints[p].parent)
      successors[p].push_back(k);
  }
  return successors;
}

/// The reduction as the vertices' skins see it.
struct SkinHandover {
  const SkeletonReduction& red;
  std::vector<std::vector<int>> successors;  // see kept_successors()
  int max_influences;
  bool resolve;  // re-solve the skins (else only hand the weights over)
};

/** The skin \p w of vertex \p vh in the reduced skeleton: its weights handed to the heirs and, when a
 *  removed joint moved it, re-solved against the example poses of \p cache (\p p and \p solver are the
 *  solve's, reused from vertex to vertex). */
template <typename Mesh>
Influences reduced_skin(const Mesh& mesh, typename Mesh::VertexHandle vh, const Influences& w, const SkinHandover& s,
                        const PoseCacheT<Mesh>& cache, EdgeProblem& p, WeightSolver& solver) {
  const SkeletonReduction& red = s.red;
  const int max_influences = s.max_influences;
  const bool resolve = s.resolve;
  bool touched = false;
  InfluenceSum handed;
  for (const JointWeight& jw : w) {
    touched |= red.heir[jw.joint] != jw.joint;
    handed.add(red.heir[jw.joint], jw.weight);
    if (resolve)
      for (int k : s.successors[jw.joint]) handed.add(k, 1e-9);  // in the support, weightless until solved
  }
  Influences start = handed.keep_heaviest(max_influences);
  if (resolve && touched && start.size() > 1) {
    // The weight solve over the kept joints, from the handed-over weights: the kept joints' skinning
    // matrices are the same in both skeletons, so the original example poses serve as they are.
    p.set_skins(start, start);
    p.resize(cache.n_poses());
    for (int j = 0; j < cache.n_poses(); ++j) {
      p.quadric[j] = cache.quadric(vh, j);
      p.set_pose(j, cache.pose(j));
    }
    p.pa = p.pb = to_eigen(mesh.point(vh));
    SolveSettings settings;
    settings.max_influences = std::min<int>(max_influences, start.size());
    start = reduce_influences(p, settings, solver);
  }
  Influences out;
  for (const JointWeight& jw : start) out.push(red.new_index[jw.joint], jw.weight);
  out.normalize();
  out.sort();
  return out;
}

}  // namespace detail

/** Reduces \p mesh's skeleton to at most \p max_joints joints, and by every minor joint whose energy is
 *  under \p energy_threshold (see reduce_skeleton()); skins keep at most
 *  \p max_influences bones, re-solved unless \p resolve is false (the weights only handed over). The example poses
 * ("m:skin_poses") are the targets of the re-solve, in the original skeleton; afterwards they are re-indexed to the
 * reduced one. Returns the joints removed. */
template <typename Mesh>
int reduce_mesh_skeleton(Mesh& mesh, int max_joints, int max_influences, bool resolve = true,
                         double energy_threshold = 0.0) {
  const Skeleton original = skeleton(mesh);
  const auto h = influences_handle(mesh);
  // The posed original surface in the example poses: what the new skins must fit.
  PoseCacheT<Mesh> cache(mesh);
  cache.build();
  const JointRemovalCost cost = detail::displacement_cost(mesh, cache, original.size());
  SkeletonReduction red = reduce_skeleton(original, clips(mesh), max_joints, cost, energy_threshold);
  const int removed = original.size() - red.skeleton.size();
  if (removed == 0) return 0;
  WeightSolver solver;
  EdgeProblem p;
  // A removed joint's kept descendants just below it now carry its motion too: a vertex it moved may
  // blend them with the heir (a shin between hip and ankle once the knee is gone), so they join the solve.
  const detail::SkinHandover handover{red, detail::kept_successors(original, red), max_influences, resolve};
  for (auto vh : mesh.vertices())
    mesh.property(h, vh) = detail::reduced_skin(mesh, vh, mesh.property(h, vh), handover, cache, p, solver);
  for (Pose& pose : example_poses(mesh)) {
    std::vector<Affine3> kept;
    for (int j = 0; j < original.size(); ++j)
      if (red.new_index[j] >= 0) kept.push_back(pose.joint[j]);
    pose.joint = kept;
  }
  skeleton(mesh) = red.skeleton;
  clips(mesh) = red.clips;
  return removed;
}

}  // namespace OpenMeshSkinned
