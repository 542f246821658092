#pragma once
// An EdgeProblem built by hand: one joint at rest, one pose, one quadric.

#include <OpenMeshSkinned/Solver/EdgeProblem.hh>

namespace omsk_test {

/// The edge \p pa - \p pb skinned wholly to joint 0, whose one pose is the rest pose, priced by \p q.
inline OpenMeshSkinned::EdgeProblem one_joint_edge(const OpenMeshSkinned::PoseQuadric& q, const Eigen::Vector3d& pa,
                                                   const Eigen::Vector3d& pb) {
  OpenMeshSkinned::EdgeProblem p;
  OpenMeshSkinned::Influences w;
  w.push(0, 1.0);
  p.set_skins(w, w);
  p.resize(1);
  p.set_pose(0, OpenMeshSkinned::Pose::identity(1));
  p.quadric[0] = q;
  p.pa = pa;
  p.pb = pb;
  return p;
}

}  // namespace omsk_test
