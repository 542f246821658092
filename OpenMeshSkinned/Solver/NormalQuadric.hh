#pragma once
/** \file NormalQuadric.hh
 *  A quadric in the rest position that prices how far a vertex moves from where the input's shading
 *  normals agree (Hoppe 1999's attribute quadric, with the attribute minimised out).
 *
 *  Each face carries the linear normal field through its three stored corner normals, N_f(x) = G_f x + c_f
 *  (constant along the face normal). At a vertex, the faces of one smoothing group (corners with the same
 *  stored normal) agree at the vertex; the quadric is their disagreement at x once the best common normal is
 *  chosen, min_n sum_f area_f |N_f(x) - n|^2. It is zero where the field is linear (a plane, a sphere) and
 *  grows where the shading bends sharply within a few faces (a smooth-shaded box's edge): moving a vertex
 *  there spreads a bent normal over faces that showed a flat one. Groups are priced apart, so a hard edge
 *  costs nothing by itself. Per vertex, the groups' quadrics are summed as a PoseQuadric, and merged vertices
 *  sum theirs, like the geometric quadrics.
 */

#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace OpenMeshSkinned {

/** The linear field through normals \p n0..n2 at corners \p p0..p2 as B = [G c] (N(x) = B [x; 1]), or false
 *  for a face too thin to carry one (its gradient would be the normals' difference over a vanishing height)
 *  or a corner without a normal. */
inline bool normal_field(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                         const Eigen::Vector3d& n0, const Eigen::Vector3d& n1, const Eigen::Vector3d& n2,
                         Eigen::Matrix<double, 3, 4>& B) {
  if (n0.squaredNorm() == 0.0 || n1.squaredNorm() == 0.0 || n2.squaredNorm() == 0.0) return false;
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d cr = e1.cross(e2);
  const double a2 = cr.norm();
  const double longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (p2 - p1).squaredNorm()});
  // Twice the area over the longest edge squared: the smallest height in longest edges.
  if (!(a2 > 1e-3 * longest)) return false;
  Eigen::Matrix3d At;  // columns e1, e2, face normal
  At.col(0) = e1;
  At.col(1) = e2;
  At.col(2) = cr / a2;
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  D.col(0) = n1 - n0;
  D.col(1) = n2 - n0;
  const Eigen::Matrix3d G = D * At.inverse();
  B.leftCols<3>() = G;
  B.col(3) = n0 - G * p0;
  return B.allFinite();
}

/** One smoothing group's sums: S1 = sum w B^T B, S2 = sum w B, W = sum w. */
struct NormalGroupSums {
  Eigen::Matrix4d S1 = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 3, 4> S2 = Eigen::Matrix<double, 3, 4>::Zero();
  double W = 0.0;

  void add(const Eigen::Matrix<double, 3, 4>& B, double w) {
    S1.noalias() += w * B.transpose() * B;
    S2 += w * B;
    W += w;
  }
  /// min over n of sum w |B x~ - n|^2, as a quadric in x~ (the Schur complement of the attribute).
  Eigen::Matrix4d quadric() const {
    if (W <= 0.0) return Eigen::Matrix4d::Zero();
    return S1 - S2.transpose() * S2 / W;
  }
};

inline PoseQuadric to_pose_quadric(const Eigen::Matrix4d& m) {
  PoseQuadric q;
  q.q[0] = m(0, 0), q.q[1] = m(0, 1), q.q[2] = m(0, 2), q.q[3] = m(0, 3);
  q.q[4] = m(1, 1), q.q[5] = m(1, 2), q.q[6] = m(1, 3);
  q.q[7] = m(2, 2), q.q[8] = m(2, 3);
  q.q[9] = m(3, 3);
  return q;
}

/** Sets \p out[v] to vertex v's normal quadric (NormalQuadric.hh), each face weighted by its area times
 *  \p weight, from the mesh's rest positions and stored halfedge normals (zero without them), on up to
 *  \p threads threads (the result does not depend on it). Corners whose unit normals agree to within
 *  \p same_cos are one smoothing group. */
template <typename Mesh>
void normal_quadrics(const Mesh& mesh, double weight, std::vector<PoseQuadric>& out, int threads = 1,
                     double same_cos = 1.0 - 1e-6) {
  out.assign(mesh.n_vertices(), PoseQuadric{});
  if (!mesh.has_halfedge_normals()) return;
  auto P = [&](typename Mesh::VertexHandle v) {
    const auto p = mesh.point(v);
    return Eigen::Vector3d(p[0], p[1], p[2]);
  };
  auto N = [&](typename Mesh::HalfedgeHandle h) {
    const auto n = mesh.normal(h);
    return Eigen::Vector3d(n[0], n[1], n[2]);
  };
  const size_t nv = mesh.n_vertices();
  threads = std::clamp(threads, 1, int(nv / 4096) + 1);
  run_on_threads(threads, [&](int t) {
    constexpr int kMaxGroups = 8;
    std::array<NormalGroupSums, kMaxGroups> sums;
    std::array<Eigen::Vector3d, kMaxGroups> key;
    Eigen::Matrix<double, 3, 4> B;
    std::vector<typename Mesh::HalfedgeHandle> fan;
    for (size_t i = nv * t / threads; i < nv * (t + 1) / threads; ++i) {
      const typename Mesh::VertexHandle v(static_cast<int>(i));
      if (mesh.has_vertex_status() && mesh.status(v).deleted()) continue;
      // In face order, not from wherever the vertex's halfedge handle starts: the same faces give the same
      // sums to the last bit, however the mesh was rebuilt.
      fan.clear();
      for (auto h : mesh.vih_range(v))
        if (!mesh.is_boundary(h)) fan.push_back(h);
      std::sort(fan.begin(), fan.end(),
                [&](auto x, auto y) { return mesh.face_handle(x).idx() < mesh.face_handle(y).idx(); });
      int groups = 0;
      for (auto h : fan) {
        const auto hn = mesh.next_halfedge_handle(h), hp = mesh.prev_halfedge_handle(h);
        const Eigen::Vector3d nv0 = N(h);
        const double len = nv0.norm();
        if (!(len > 0.0)) continue;
        const Eigen::Vector3d p0 = P(v), p1 = P(mesh.to_vertex_handle(hn)), p2 = P(mesh.to_vertex_handle(hp));
        if (!normal_field(p0, p1, p2, nv0 / len, N(hn).normalized(), N(hp).normalized(), B)) continue;
        const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
        int g = 0;
        while (g < groups && key[g].dot(nv0 / len) < same_cos) ++g;
        if (g == groups) {
          if (groups == kMaxGroups) continue;  // more smoothing groups than any real vertex has
          key[g] = nv0 / len;
          sums[g] = NormalGroupSums{};
          ++groups;
        }
        sums[g].add(B, area * weight);
      }
      Eigen::Matrix4d q = Eigen::Matrix4d::Zero();
      for (int g = 0; g < groups; ++g) q += sums[g].quadric();
      out[i] = to_pose_quadric(q);
    }
  });
}

}  // namespace OpenMeshSkinned
