#pragma once
/** \file ExampleFrames.hh
 *  The positions every vertex takes in the mesh's example poses ("m:skin_poses"), morph offsets and skin
 *  applied: the frames the deformation modules learn from, whether the mesh has a skeleton or not.
 */

#include "OpenMeshSkinned/Deform/DeformationAnalysis.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <vector>

namespace OpenMeshSkinned {

/// Rest positions by vertex index.
template <typename Mesh>
FramePoints rest_points(const Mesh& mesh) {
  FramePoints p(mesh.n_vertices());
  for (auto vh : mesh.all_vertices()) p[vh.idx()] = to_eigen(mesh.point(vh));
  return p;
}

/// Posed positions in each example pose (std::invalid_argument when the mesh has none:
/// required_example_poses()).
template <typename Mesh>
std::vector<FramePoints> example_frame_points(const Mesh& mesh) {
  std::vector<FramePoints> out;
  for (const Pose& pose : required_example_poses(mesh)) out.push_back(skin_positions(mesh, pose));
  return out;
}

/// The Garland-Heckbert plane quadric of the triangle \p a \p b \p c, weighted by its area (zero when it
/// has none).
template <typename Quadric>
Quadric area_plane_quadric(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len > 0.0)) return Quadric(0.0, 0.0, 0.0, 0.0);
  const Eigen::Vector3d u = n / len;
  Quadric q(u.x(), u.y(), u.z(), -u.dot(a));
  q *= 0.5 * len;
  return q;
}

}  // namespace OpenMeshSkinned
