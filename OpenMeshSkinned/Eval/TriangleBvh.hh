#pragma once
/** \file TriangleBvh.hh
 *  The nearest point of a triangle soup to a query point: a bounding-volume hierarchy over the triangles
 *  (median splits of their centroids along the widest axis, a few triangles a leaf), searched nearer box
 *  first. The answer is the triangle of least (squared distance, index), both as closest_barycentric()
 *  computes them, so it does not depend on the search order or a hint: it is what trying every triangle
 *  would give, bit for bit. A hint (a triangle near the answer, such as the one a moving point hit last
 *  time) only makes the search shorter.
 */

#include "OpenMeshSkinned/Eval/TriangleSoup.hh"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace OpenMeshSkinned {

class TriangleBvh {
public:
  TriangleBvh() = default;
  /// Builds the hierarchy of \p soup's triangles (copied: the soup need not outlive it). Throws
  /// std::out_of_range for a corner index outside its points.
  explicit TriangleBvh(const TriangleSoup& soup);

  /** Moves the triangles' corners to \p points (the soup's triangles, posed again: the same indices),
   *  keeping the hierarchy and its memory. Answers stay exact; they come slower the more the shape moved
   *  from the one the hierarchy was split in. Throws std::out_of_range, changing nothing, when \p points
   *  has fewer points than the triangles use. */
  void refit(const std::vector<Eigen::Vector3d>& points);

  bool empty() const { return slots_.empty(); }
  /// The soup's triangles it was built from (what refit() poses again).
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  size_t size() const { return slots_.size(); }
  /** Where soup triangle \p triangle comes in the hierarchy's leaf order: triangles close in rank are close
   *  in space, so queries taken in the rank order of where they lie touch the same boxes one after another.
   *  -1 for an index outside the soup. */
  int rank(int triangle) const { return triangle >= 0 && size_t(triangle) < slot_of_.size() ? slot_of_[triangle] : -1; }

  /** The squared distance from \p q to the soup, with \p triangle set to the nearest triangle's index in
   *  the soup (-1 and infinity when there is none). \p hint: a triangle to start from (any value outside
   *  the soup's range is ignored). */
  double nearest(const Eigen::Vector3d& q, int& triangle, int hint = -1) const;

  /** The squared distance from \p q to soup triangle \p triangle alone, computed as nearest() computes it:
   *  never less than nearest()'s answer, so a bound that spares the search where any upper bound will do.
   *  Infinity for an index outside the soup. */
  double distance2_to(const Eigen::Vector3d& q, int triangle) const;

private:
  struct Node {
    double lo[3], hi[3];
    int32_t first;  // a leaf: its first slot; else: its children, first and first + 1
    int32_t count;  // a leaf: its slots; 0: an inner node
  };
  struct Slot {
    Eigen::Vector3d corner[3];
    float normal[3];  // unit, or zero for a degenerate triangle: a lower bound on the distance, in float
    int id;           // the triangle's index in the soup
  };
  double box_distance2(const Node& n, const Eigen::Vector3d& q) const;
  // Considers slot \p s for \p q: takes it when it is nearer (ties: the lower index).
  void consider(int s, const Eigen::Vector3d& q, double& best, int& best_id) const;

  std::vector<Node> nodes_;
  std::vector<Slot> slots_;                    // in leaf order
  std::vector<int> slot_of_;                   // per soup triangle, its slot
  std::vector<std::array<int, 3>> triangles_;  // the soup's, to refit from
  int max_index_ = 0;                          // the largest corner index they use
};

}  // namespace OpenMeshSkinned
