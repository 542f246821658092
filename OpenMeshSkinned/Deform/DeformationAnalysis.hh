#pragma once
/** \file DeformationAnalysis.hh
 *  How much a mesh deforms between neighbouring faces over an animation, for meshes with or without a
 *  skeleton (Lee et al., "Segmenting a deforming mesh into near-rigid components", eq. 1-4; the
 *  deformation-analysis report, eq. 5-8).
 *
 *  Positions are given per frame as one array indexed by vertex index; the reference frame is the one
 *  every other frame is compared with (the rest shape).
 */

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace OpenMeshSkinned {

using FramePoints = std::vector<Eigen::Vector3d>;

/** Lee eq. 1-3 (Sumner and Popovic's construction): the triangle gets a fourth vertex
 *  v4 = v1 + (v2-v1)x(v3-v1) / sqrt(|(v2-v1)x(v3-v1)|), so that its normal direction scales like its
 *  edges, and the deformation gradient is M = V~ V^-1 with V = [v2-v1, v3-v1, v4-v1]. Returns false (and
 *  leaves \p M alone) when the reference triangle has no area. */
inline bool deformation_gradient(const std::array<Eigen::Vector3d, 3>& ref, const std::array<Eigen::Vector3d, 3>& def,
                                 Eigen::Matrix3d& M) {
  auto frame = [](const std::array<Eigen::Vector3d, 3>& t) {
    const Eigen::Vector3d e1 = t[1] - t[0], e2 = t[2] - t[0], n = e1.cross(e2);
    const double len = n.norm();
    Eigen::Matrix3d V;
    V.col(0) = e1;
    V.col(1) = e2;
    V.col(2) = len > 0.0 ? Eigen::Vector3d(n / std::sqrt(len)) : Eigen::Vector3d::Zero();
    return V;
  };
  const Eigen::Matrix3d V = frame(ref);
  Eigen::FullPivLU<Eigen::Matrix3d> lu(V);
  if (!lu.isInvertible()) return false;
  M = frame(def) * lu.inverse();
  return true;
}

/// Per face and frame of an animation: its deformation gradient from the reference frame, and whether it
/// has one (a face of no area in the reference frame has none).
template <typename Mesh>
struct FaceGradients {
  std::vector<std::vector<Eigen::Matrix3d>> M;  // [frame][face index]
  std::vector<char> valid;                      // [face index]

  FaceGradients(const Mesh& mesh, const FramePoints& ref, const std::vector<FramePoints>& frames) {
    valid.assign(mesh.n_faces(), 0);
    M.assign(frames.size(), std::vector<Eigen::Matrix3d>(mesh.n_faces(), Eigen::Matrix3d::Identity()));
    for (auto fh : mesh.faces()) {
      std::array<int, 3> v{};
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) v[k++] = vh.idx();
      const std::array<Eigen::Vector3d, 3> r = {ref[v[0]], ref[v[1]], ref[v[2]]};
      bool ok = true;
      for (size_t t = 0; t < frames.size() && ok; ++t)
        ok = deformation_gradient(r, {frames[t][v[0]], frames[t][v[1]], frames[t][v[2]]}, M[t][fh.idx()]);
      valid[fh.idx()] = ok;
    }
  }
};

/// Distance between the centroids of two faces in the reference frame (Lee's Geod for adjacent faces).
template <typename Mesh>
double centroid_distance(const Mesh& mesh, const FramePoints& ref, typename Mesh::FaceHandle a,
                         typename Mesh::FaceHandle b) {
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (auto vh : mesh.fv_range(a)) ca += ref[vh.idx()];
  for (auto vh : mesh.fv_range(b)) cb += ref[vh.idx()];
  return (ca - cb).norm() / 3.0;
}

/** Per edge (by edge index; 0 on boundary edges and next to a face without a gradient): the largest over
 *  the frames of ||M_i^t - M_j^t||_F^2 between the two faces it separates, the report's deformation
 *  difference (eq. 6-7). With \p per_length, divided by the distance between their centroids: Lee's
 *  deformation distance D_ij (eq. 4), which makes small faces in bending regions count as much as the
 *  large ones around them. */
template <typename Mesh>
std::vector<double> deformation_distances(const Mesh& mesh, const FramePoints& ref, const FaceGradients<Mesh>& g,
                                          bool per_length) {
  std::vector<double> d(mesh.n_edges(), 0.0);
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh)) continue;
    const auto fa = mesh.face_handle(mesh.halfedge_handle(eh, 0));
    const auto fb = mesh.face_handle(mesh.halfedge_handle(eh, 1));
    if (!g.valid[fa.idx()] || !g.valid[fb.idx()]) continue;
    double worst = 0.0;
    for (const auto& Mt : g.M) worst = std::max(worst, (Mt[fa.idx()] - Mt[fb.idx()]).squaredNorm());
    if (per_length) {
      const double geod = centroid_distance(mesh, ref, fa, fb);
      worst = geod > 0.0 ? worst / geod : 0.0;
    }
    d[eh.idx()] = worst;
  }
  return d;
}

/** The report's face importance (eq. 8): the average of the deformation differences (eq. 7) across a
 *  face's edges with a neighbour. High at joints and other bending regions, zero inside parts that move
 *  rigidly. By face index. */
template <typename Mesh>
std::vector<double> face_importance(const Mesh& mesh, const FramePoints& ref, const std::vector<FramePoints>& frames) {
  const FaceGradients<Mesh> g(mesh, ref, frames);
  const std::vector<double> d = deformation_distances(mesh, ref, g, false);
  std::vector<double> w(mesh.n_faces(), 0.0);
  for (auto fh : mesh.faces()) {
    double sum = 0.0;
    int n = 0;
    for (auto heh : mesh.fh_range(fh)) {
      const auto eh = mesh.edge_handle(heh);
      if (mesh.is_boundary(eh)) continue;
      sum += d[eh.idx()];
      ++n;
    }
    w[fh.idx()] = n > 0 ? sum / n : 0.0;
  }
  return w;
}

}  // namespace OpenMeshSkinned
