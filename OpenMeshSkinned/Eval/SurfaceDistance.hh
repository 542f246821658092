#pragma once
/** \file SurfaceDistance.hh
 *  Metro-style distance between two triangle surfaces (Cignoni et al.): points sampled by area on each
 *  surface, plus its vertices, each measured to the nearest point of the other surface (TriangleBvh.hh).
 *  Symmetric: both directions are pooled.
 */

#include "OpenMeshSkinned/Eval/TriangleSoup.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace OpenMeshSkinned {

struct SurfaceDistance {
  double rms = 0.0;        ///< root mean square of all sample distances (both directions)
  double hausdorff = 0.0;  ///< largest sample distance (both directions)
  size_t samples = 0;
};

/** A surface ready to be measured against, any number of times: its triangles' search hierarchy, built
 *  once, and its own samples (its vertices plus \p samples points by area, drawn with \p seed). A posed
 *  original is built (or posed again, repose()) once per frame and measured against every LOD and method;
 *  safe to share between threads. */
class MeasuredSurface {
public:
  MeasuredSurface(const TriangleSoup& soup, size_t samples, uint64_t seed);
  ~MeasuredSurface();
  MeasuredSurface(MeasuredSurface&&) noexcept;
  MeasuredSurface& operator=(MeasuredSurface&&) noexcept;

  /** The same surface in another pose: \p soup has the triangles it was built with (same indices) and
   *  moved points. Its samples are drawn again as the constructor would draw them, and the search hierarchy
   *  is moved rather than built again (no allocation for it), so every distance is what a surface built
   *  from \p soup would give. Throws std::invalid_argument for other triangles. */
  void repose(const TriangleSoup& soup);

  /// Distance from \p p to the nearest point of the surface (infinity for a surface without triangles).
  double distance(const Eigen::Vector3d& p) const;
  /// As distance(), and the index (in the soup) of the triangle that nearest point lies on (-1 when none).
  double distance(const Eigen::Vector3d& p, int& triangle) const;
  /// As above, starting from triangle \p hint (ignored when out of range): the same nearest point, found
  /// faster when the hint lies near it (a query that moved a little since it last hit that triangle).
  double distance(const Eigen::Vector3d& p, int& triangle, int hint) const;

  /// Where soup triangle \p triangle comes in the hierarchy's leaf order (TriangleBvh::rank; -1 outside the soup).
  int rank(int triangle) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

private:
  std::unique_ptr<Impl> impl_;
};

/** \p slot's surface in the pose \p soup: built there (with \p samples and \p seed) when \p slot is empty,
 *  else posed again (MeasuredSurface::repose). For a thread measuring the same surface pose after pose. */
const MeasuredSurface& posed_surface(std::unique_ptr<MeasuredSurface>& slot, const TriangleSoup& soup, size_t samples,
                                     uint64_t seed);

/// Distance between two prepared surfaces: each one's samples to the other's triangles, pooled.
SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b);

/** The same distance, each vertex's query starting from the triangle it hit before: \p a_hints holds, per
 *  vertex of \p a, the triangle of \p b nearest to it last time (-1 or missing: none), and is updated;
 *  \p b_hints the same for \p b's vertices (area samples are searched from the one before them: hints of
 *  their own, from the frame before, measured no faster). For the same surfaces measured again in another
 *  pose (the frames of a clip): the numbers of surface_distance(a, b), found faster.
 *
 *  \p counted_vertices (0: no limit) caps how many of a surface's vertices are measured for the RMS: of a
 *  denser surface, every k-th in the hierarchy's leaf order (so spread evenly over it), each standing for the
 *  k around it, so the RMS estimates the one every vertex gives. The Hausdorff distance stays exact: every
 *  other vertex is measured first to its hint's triangle, an upper bound on its distance, and searched only
 *  when that bound could raise the maximum; its hint is updated only then. For dense originals, whose
 *  vertices are most of the queries. */
SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>& a_hints,
                                 std::vector<int>& b_hints, size_t counted_vertices = 0);

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
