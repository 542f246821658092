#pragma once
/** \file VertexQuadrics.hh
 *  Per-vertex Garland-Heckbert quadrics of a mesh in one or more configurations (poses), and the optimal
 *  point of a summed quadric near an edge.
 */

#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"
#include "OpenMeshSkinned/Solver/TruncatedSolve.hh"

#include <algorithm>
#include <vector>

namespace OpenMeshSkinned {

/// Two faces meeting at an edge with normals closer to opposite than this (cosine) fold a sheet back on
/// itself (a wing, a flap, an ear modelled as two layers): their planes nearly coincide and cannot see the
/// sheet's outline pulled inwards, so the edge gets the planes an open border gets.
inline constexpr double kFoldEdgeCos = -0.7;

/// An attribute seam (Seams.hh: material boundary, textured UV seam, hard edge) gets the planes of a fold at
/// this fraction of their weight. Measured with bench/peer-vs-gltfpack.sh on faerie and sydney: at 1 the
/// texture deviation is lowest but the held-out RMS rises; a quarter keeps most of the texture's gain for a
/// smaller rise (bench/README.md, "Defaults chosen by measurement").
inline constexpr double kSeamPlaneWeight = 0.25;

namespace detail {

/// The (unnormalised) normal of face \p fh in configuration \p j.
template <typename Mesh, typename Pos>
Eigen::Vector3d face_normal_in(const Mesh& mesh, typename Mesh::FaceHandle fh, int j, Pos& pos) {
  auto fv = mesh.cfv_iter(fh);
  const Eigen::Vector3d f0 = pos(*fv++, j), f1 = pos(*fv++, j), f2 = pos(*fv, j);
  return (f1 - f0).cross(f2 - f0);
}

/// Per edge: 0, or the weight of the planes its two faces get (1 where the sheet folds back on itself in
/// every configuration, kSeamPlaneWeight at an attribute seam).
template <typename Mesh, typename Pos>
std::vector<double> sheet_edge_weights(const Mesh& mesh, int n_poses, Pos pos) {
  const std::vector<char> seams = attribute_seams(mesh);
  std::vector<double> weight(mesh.n_edges(), 0.0);
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh)) continue;
    const auto h0 = mesh.halfedge_handle(eh, 0);
    const auto f0 = mesh.face_handle(h0), f1 = mesh.face_handle(mesh.opposite_halfedge_handle(h0));
    // Folded in every configuration: a sheet as modelled, not a crease a pose bends into the skin (the
    // inside of a bent knee), which would pin the joint's geometry. A seam is cut in what the surface shows,
    // whatever its shape.
    bool folded = n_poses > 0;
    for (int j = 0; j < n_poses && folded; ++j) {
      const Eigen::Vector3d n0 = face_normal_in(mesh, f0, j, pos), n1 = face_normal_in(mesh, f1, j, pos);
      const double l = n0.norm() * n1.norm();
      folded = l > 0.0 && n0.dot(n1) < kFoldEdgeCos * l;
    }
    if (folded || seams[eh.idx()]) weight[eh.idx()] = folded ? 1.0 : kSeamPlaneWeight;
  }
  return weight;
}

/// accumulate_quadrics() for the configurations [j0, j1), given sheet_edge_weights().
template <typename Mesh, typename Pos, typename Quadric, typename FaceWeight>
void accumulate_configurations(const Mesh& mesh, int j0, int j1, Pos pos, Quadric quadric, FaceWeight face_weight,
                               const std::vector<double>& sheet_weight) {
  using VH = typename Mesh::VertexHandle;
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const VH a = *fv++, b = *fv++, c = *fv;
    for (int j = j0; j < j1; ++j) {
      const Eigen::Vector3d pa = pos(a, j), pb = pos(b, j), pc = pos(c, j);
      Eigen::Vector3d n = (pb - pa).cross(pc - pa);
      const double len = n.norm();
      if (len <= 0.0) continue;
      n /= len;
      const PoseQuadric q = PoseQuadric::plane(n, -n.dot(pa), 0.5 * len * face_weight(fh));
      quadric(a, j) += q;
      quadric(b, j) += q;
      quadric(c, j) += q;
    }
  }
  // The plane through the edge (a, b) of face fh, perpendicular to the face.
  auto edge_plane = [&](VH a, VH b, typename Mesh::FaceHandle fh, const Eigen::Vector3d& face_n, int j,
                        double w = 1.0) {
    const Eigen::Vector3d e = pos(b, j) - pos(a, j);
    Eigen::Vector3d n = e.cross(face_n);
    const double len = n.norm();
    if (len <= 0.0) return;
    n /= len;
    const PoseQuadric q = PoseQuadric::plane(n, -n.dot(pos(a, j)), w * e.squaredNorm() * face_weight(fh));
    quadric(a, j) += q;
    quadric(b, j) += q;
  };
  for (auto heh : mesh.halfedges()) {
    if (!mesh.is_boundary(heh)) continue;
    const auto fh = mesh.face_handle(mesh.opposite_halfedge_handle(heh));
    const VH a = mesh.from_vertex_handle(heh), b = mesh.to_vertex_handle(heh);
    for (int j = j0; j < j1; ++j) edge_plane(a, b, fh, face_normal_in(mesh, fh, j, pos), j);
  }
  for (auto eh : mesh.edges()) {
    const double w = sheet_weight[eh.idx()];
    if (w == 0.0) continue;
    const auto h0 = mesh.halfedge_handle(eh, 0);
    const auto f0 = mesh.face_handle(h0), f1 = mesh.face_handle(mesh.opposite_halfedge_handle(h0));
    const VH a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
    for (int j = j0; j < j1; ++j) {
      edge_plane(a, b, f0, face_normal_in(mesh, f0, j, pos), j, w);
      edge_plane(a, b, f1, face_normal_in(mesh, f1, j, pos), j, w);
    }
  }
}

/// Shares the configurations [0, n_poses) out among up to \p threads threads in contiguous ranges.
template <typename F>
void on_configuration_ranges(int n_poses, int threads, F f) {
  threads = std::clamp(threads, 1, std::max(1, n_poses));
  run_on_threads(threads, [&](int t) { f(n_poses * t / threads, n_poses * (t + 1) / threads); });
}

}  // namespace detail

/** Adds to \p quadric(v, j) the area-weighted planes of v's faces in configuration j (positions
 *  \p pos(v, j)), for j in [0, n_poses), each also weighted by \p face_weight(face handle), plus, at open
 *  borders, a plane through the border edge perpendicular to its face, weighted by the squared edge length
 *  (and its face's weight), so that borders do not shrink away; the same for each face at an edge where the
 *  sheet folds back on itself (kFoldEdgeCos) in every configuration, and at kSeamPlaneWeight of that for each
 *  face at an attribute seam (attribute_seams()). With \p threads > 1 the configurations are shared out among
 *  threads (\p pos and \p quadric are then called concurrently for different j); each quadric gets the same
 *  planes in the same order whatever the thread count. */
template <typename Mesh, typename Pos, typename Quadric, typename FaceWeight>
void accumulate_quadrics(const Mesh& mesh, int n_poses, Pos pos, Quadric quadric, FaceWeight face_weight,
                         int threads = 1) {
  const std::vector<double> sheet_weight = detail::sheet_edge_weights(mesh, n_poses, pos);
  detail::on_configuration_ranges(n_poses, threads, [&](int j0, int j1) {
    detail::accumulate_configurations(mesh, j0, j1, pos, quadric, face_weight, sheet_weight);
  });
}

/** accumulate_quadrics() one configuration at a time, into a table of its own: \p done(j, sums) receives
 *  every vertex's quadric in configuration j (sums[v.idx()], from zero), on the thread that summed them.
 *  Each thread holds one table at a time, not one per configuration: for a caller that stores them in
 *  another form. The same planes in the same order as accumulate_quadrics(). */
template <typename Mesh, typename Pos, typename FaceWeight, typename Done>
void accumulate_quadrics_by_configuration(const Mesh& mesh, int n_poses, Pos pos, FaceWeight face_weight, Done done,
                                          int threads = 1) {
  const std::vector<double> sheet_weight = detail::sheet_edge_weights(mesh, n_poses, pos);
  detail::on_configuration_ranges(n_poses, threads, [&](int j0, int j1) {
    std::vector<PoseQuadric> sum;
    for (int j = j0; j < j1; ++j) {
      sum.assign(mesh.n_vertices(), PoseQuadric{});
      detail::accumulate_configurations(
          mesh, j, j + 1, pos, [&sum](typename Mesh::VertexHandle v, int) -> PoseQuadric& { return sum[v.idx()]; },
          face_weight, sheet_weight);
      done(j, static_cast<const std::vector<PoseQuadric>&>(sum));
    }
  });
}

/// accumulate_quadrics() with every face weighing 1.
template <typename Mesh, typename Pos, typename Quadric>
void accumulate_quadrics(const Mesh& mesh, int n_poses, Pos pos, Quadric quadric) {
  accumulate_quadrics(mesh, n_poses, pos, quadric, [](typename Mesh::FaceHandle) { return 1.0; });
}

/** The point minimising the static quadric \p q for the edge (pa, pb): directions the quadric barely
 *  constrains stay at the midpoint (truncated_solve()), a minimiser further than one
 *  edge length from the midpoint is refused, and the endpoints and midpoint compete with it. */
inline Eigen::Vector3d optimal_point(const PoseQuadric& q, const Eigen::Vector3d& pa, const Eigen::Vector3d& pb) {
  const Eigen::Vector3d mid = 0.5 * (pa + pb);
  Eigen::Vector3d best = mid;
  double be = q(mid);
  for (const Eigen::Vector3d& c : {pa, pb})
    if (q(c) < be) {
      be = q(c);
      best = c;
    }
  Eigen::Vector3d v;
  if (!truncated_solve(q.A(), -q.b(), mid, v)) return best;
  if (v.allFinite() && (v - mid).squaredNorm() <= (pa - pb).squaredNorm() && q(v) < be) best = v;
  return best;
}

}  // namespace OpenMeshSkinned
