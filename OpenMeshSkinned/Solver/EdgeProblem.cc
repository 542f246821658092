#include "OpenMeshSkinned/Solver/EdgeProblem.hh"

#include <algorithm>

namespace OpenMeshSkinned {

void EdgeProblem::set_skins(const Influences& wa, const Influences& wb) {
  support = 0;
  for (const JointWeight& jw : wa) joint[support++] = jw.joint;
  for (const JointWeight& jw : wb)
    if (std::find(joint.begin(), joint.begin() + support, jw.joint) == joint.begin() + support)
      joint[support++] = jw.joint;
  start.resize(support);
  for (int k = 0; k < support; ++k) start[k] = 0.5 * (wa.weight_of(joint[k]) + wb.weight_of(joint[k]));
}

void EdgeProblem::resize(int n) {
  poses = n;
  quadric.resize(n);
  if (!shared_poses) transform.resize(static_cast<size_t>(n) * kMaxSupport);
}

void EdgeProblem::set_pose(int j, const Pose& pose) {
  for (int k = 0; k < support; ++k) transform[j * kMaxSupport + k] = pose.joint[joint[k]];
}

}  // namespace OpenMeshSkinned
