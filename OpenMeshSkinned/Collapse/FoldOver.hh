#pragma once
/** \file FoldOver.hh
 *  The fold-over test of one collapse, in any number of poses.
 */

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <vector>

namespace OpenMeshSkinned {

/** Whether moving corner \p pc of the triangle (pc, pa, pb) to \p p turns its normal by more than
 *  acos(min_cos), or leaves it degenerate. A triangle that was degenerate before cannot turn. */
inline bool face_folds(const Eigen::Vector3d& pc, const Eigen::Vector3d& pa, const Eigen::Vector3d& pb,
                       const Eigen::Vector3d& p, double min_cos) {
  const Eigen::Vector3d n_old = (pa - pc).cross(pb - pc);
  const Eigen::Vector3d da = pa - p, db = pb - p;
  const Eigen::Vector3d n_new = da.cross(db);
  const double l2_new = n_new.squaredNorm(), l2_old = n_old.squaredNorm();
  // Degenerate: twice the area tiny against the longest edge squared. |pa - pb|^2 <= 4 max(|da|^2, |db|^2),
  // so the third edge is measured only when the face is near that limit.
  const double m = std::max(da.squaredNorm(), db.squaredNorm());
  if (l2_new <= 16e-20 * m * m) {
    const double scale = std::max(m, (pa - pb).squaredNorm());
    if (l2_new <= 1e-20 * scale * scale) return true;
  }
  if (l2_old <= 0.0) return false;
  const double d = n_new.dot(n_old);
  // d < min_cos |n_new||n_old|, without square roots.
  return min_cos >= 0.0 ? (d < 0.0 || d * d < min_cos * min_cos * l2_new * l2_old)
                        : (d < 0.0 && d * d > min_cos * min_cos * l2_new * l2_old);
}

/// A face that survives a collapse, as vertex indices (center, a, b): the center becomes the merged vertex.
using RingFace = std::array<int, 3>;

/** The faces around \p v0 and \p v1 that survive collapsing one into the other (those without both); with
 *  a valid \p corner, only those that have it as a corner. */
template <typename Mesh>
void surviving_faces(const Mesh& mesh, typename Mesh::VertexHandle v0, typename Mesh::VertexHandle v1,
                     std::vector<RingFace>& out, typename Mesh::VertexHandle corner = typename Mesh::VertexHandle()) {
  out.clear();
  for (const auto center : {v0, v1}) {
    const auto other = center == v0 ? v1 : v0;
    for (auto heh : mesh.voh_range(center)) {
      if (mesh.is_boundary(heh)) continue;
      const auto a = mesh.to_vertex_handle(heh);
      const auto b = mesh.to_vertex_handle(mesh.next_halfedge_handle(heh));
      if (a != other && b != other && (!corner.is_valid() || a == corner || b == corner))
        out.push_back({center.idx(), a.idx(), b.idx()});
    }
  }
}

/** Whether any of \p faces folds in any of \p poses poses, with \p posed(vertex index, pose) the posed
 *  positions before the collapse and \p merged(pose) the merged vertex's. Pose by pose: the merged vertex
 *  is posed once per pose, and a fold is usually found in the first poses. */
template <typename Posed, typename Merged>
bool folds_in_any_pose(const std::vector<RingFace>& faces, int poses, Posed posed, Merged merged, double min_cos) {
  for (int j = 0; j < poses; ++j) {
    const Eigen::Vector3d p = merged(j);
    for (const RingFace& f : faces)
      if (face_folds(posed(f[0], j), posed(f[1], j), posed(f[2], j), p, min_cos)) return true;
  }
  return false;
}

}  // namespace OpenMeshSkinned
