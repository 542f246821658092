#pragma once
/** \file SurfaceDistance.hh
 *  Metro-style distance between two triangle surfaces (Cignoni et al.): points sampled by area on each
 *  surface, plus its vertices, each measured to the nearest point of the other surface through CGAL's
 *  AABB tree. Symmetric: both directions are pooled.
 */

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace OpenMeshSkinned {

/// A triangle soup: positions and index triples.
struct TriangleSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

struct SurfaceDistance {
  double rms = 0.0;        ///< root mean square of all sample distances (both directions)
  double hausdorff = 0.0;  ///< largest sample distance (both directions)
  size_t samples = 0;
};

/** A surface ready to be measured against, any number of times: its triangles in an AABB tree, built once,
 *  and its own samples (its vertices plus \p samples points by area, drawn with \p seed). A posed original
 *  is built once per frame and measured against every LOD and method; safe to share between threads. */
class MeasuredSurface {
public:
  /// Every triangle gives a start point to CGAL's search for the nearest point (the default).
  static constexpr size_t kAllHintPoints = static_cast<size_t>(-1);
  /** \p hint_points: how many of the triangles, evenly strided, give a start point to the search (CGAL's
   *  kd-tree of hints, built here). Many queries pay for a start point on every triangle; a few thousand
   *  queries on a large surface are answered as fast from a few thousand start points, and the tree of all
   *  of them would cost more than the queries. 0: none (queries without a hint start from the first
   *  triangle). The nearest points found do not depend on it. */
  MeasuredSurface(const TriangleSoup& soup, size_t samples, uint64_t seed, size_t hint_points = kAllHintPoints);
  ~MeasuredSurface();
  MeasuredSurface(MeasuredSurface&&) noexcept;
  MeasuredSurface& operator=(MeasuredSurface&&) noexcept;

  /// Distance from \p p to the nearest point of the surface (infinity for a surface without triangles).
  double distance(const Eigen::Vector3d& p) const;
  /// As distance(), and the index (in the soup) of the triangle that nearest point lies on (-1 when none).
  double distance(const Eigen::Vector3d& p, int& triangle) const;
  /// As above, starting from triangle \p hint (ignored when out of range): the same nearest point, found
  /// faster when the hint lies near it (a query that moved a little since it last hit that triangle).
  double distance(const Eigen::Vector3d& p, int& triangle, int hint) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

private:
  std::unique_ptr<Impl> impl_;
};

/// Distance between two prepared surfaces: each one's samples to the other's triangles, pooled.
SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b);

/** The same distance, each vertex's query starting from the triangle it hit before: \p a_hints holds, per
 *  vertex of \p a, the triangle of \p b nearest to it last time (-1 or missing: none), and is updated;
 *  \p b_hints the same for \p b's vertices (area samples fall elsewhere in every pose, and keep the surface's
 *  own start points). For the same surfaces measured again in another pose (the frames of a clip): the
 *  numbers of surface_distance(a, b), found faster. */
SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>& a_hints,
                                 std::vector<int>& b_hints);

/** Distance between \p a and \p b with about \p samples_per_surface area samples on each (plus vertices).
 *  Deterministic for a given \p seed. */
SurfaceDistance surface_distance(const TriangleSoup& a, const TriangleSoup& b, size_t samples_per_surface = 20000,
                                 uint64_t seed = 1);

/// The mesh's non-deleted faces, with vertices posed by \p pose (linear blend skinning).
template <typename Mesh>
TriangleSoup posed_soup(const Mesh& mesh, const Pose& pose) {
  TriangleSoup s;
  s.points = skin_positions(mesh, pose);
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const int i = (fv++)->idx(), j = (fv++)->idx(), k = fv->idx();
    s.triangles.push_back({i, j, k});
  }
  return s;
}

/** The largest distance from a vertex of \p original to \p lod, both posed by each of \p poses: one-sided, at
 *  the original's vertices (what ModDeviationBoundT bounds while decimating). */
template <typename Mesh>
double worst_vertex_deviation(const Mesh& original, const Mesh& lod, const std::vector<Pose>& poses) {
  double worst = 0.0;
  for (const Pose& pose : poses) {
    const MeasuredSurface surface(posed_soup(lod, pose), 0, 1);
    const std::vector<Eigen::Vector3d> p = skin_positions(original, pose);
    for (auto vh : original.vertices())
      if (!original.is_isolated(vh)) worst = std::max(worst, surface.distance(p[vh.idx()]));
  }
  return worst;
}

/// Diagonal of the bounding box of the mesh's non-deleted vertices (rest pose).
template <typename Mesh>
double bbox_diagonal(const Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(vh));
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return mesh.n_vertices() ? (hi - lo).norm() : 0.0;
}

}  // namespace OpenMeshSkinned
