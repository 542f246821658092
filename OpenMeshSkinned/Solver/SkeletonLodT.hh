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
  // Beyond the paper's energy order: a joint costs what handing its weights to the heir moves the
  // vertices, sum over vertices of weight x the largest displacement over the example poses.
  std::vector<std::vector<std::pair<int, double>>> bound(original.size());  // joint -> (vertex, weight)
  for (auto vh : mesh.vertices())
    for (const JointWeight& jw : mesh.property(h, vh)) bound[jw.joint].push_back({vh.idx(), jw.weight});
  const JointRemovalCost cost = [&](int j, int heir) {
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
  SkeletonReduction red = reduce_skeleton(original, clips(mesh), max_joints, cost, energy_threshold);
  const int removed = original.size() - red.skeleton.size();
  if (removed == 0) return 0;
  WeightSolver solver;
  SolveSettings settings;
  settings.max_influences = max_influences;
  EdgeProblem p;
  // A removed joint's kept descendants just below it now carry its motion too: a vertex it moved may
  // blend them with the heir (a shin between hip and ankle once the knee is gone), so they join the solve.
  std::vector<std::vector<int>> successors(original.size());
  for (int k = 0; k < original.size(); ++k) {
    if (red.new_index[k] < 0) continue;
    for (int p = original.joints[k].parent; p >= 0 && red.new_index[p] < 0; p = original.joints[p].parent)
      successors[p].push_back(k);
  }
  for (auto vh : mesh.vertices()) {
    const Influences& w = mesh.property(h, vh);
    bool touched = false;
    InfluenceSum handed;
    for (const JointWeight& jw : w) {
      touched |= red.heir[jw.joint] != jw.joint;
      handed.add(red.heir[jw.joint], jw.weight);
      if (resolve)
        for (int k : successors[jw.joint]) handed.add(k, 1e-9);  // in the support, weightless until solved
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
      SolveSettings s = settings;
      s.max_influences = std::min<int>(max_influences, start.size());
      start = reduce_influences(p, s, solver);
    }
    Influences out;
    for (const JointWeight& jw : start) out.push(red.new_index[jw.joint], jw.weight);
    out.normalize();
    out.sort();
    mesh.property(h, vh) = out;
  }
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
