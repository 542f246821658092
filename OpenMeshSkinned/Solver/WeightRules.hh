#pragma once
/** \file WeightRules.hh
 *  Weight-update rules for the cost models that do not solve for weights: the merged vertex of an edge
 *  (v0, v1), placed at p, gets a blend of the endpoints' skins.
 *
 *  - NearestEndpoint: the skin of the endpoint closer to p (ties: v1, the survivor of a halfedge collapse).
 *  - DistanceInterpolation (DeCoro & Rusinkiewicz): t = d0 / (d0 + d1), w = (1 - t) w0 + t w1, with d0, d1
 *    the distances from p to v0, v1.
 *  - PowerSkinning (Savoye & Meyer 4.2.4): each endpoint weighs (D - d_i) / Dinv with D = sum d_i and
 *    Dinv = sum (D - d_i). For an edge (two vertices) Dinv = D and the weights are d1/D and d0/D: the same
 *    blend as DistanceInterpolation. It is kept as its own rule because the formula differs for larger
 *    clusters, and so the comparison in the app names what the paper names.
 *
 *  All rules give weights >= 0 summing to one; a cap keeps the heaviest n and renormalises (these methods
 *  have no error model for weights, so the paper's re-solve does not apply).
 */

#include "OpenMeshSkinned/Skin/Influences.hh"

#include <Eigen/Core>

#include <algorithm>

#include <string>

namespace OpenMeshSkinned {

enum class WeightRule { NearestEndpoint, DistanceInterpolation, PowerSkinning };

/// The merged skin for an edge (p0, w0)-(p1, w1) whose vertex lands at \p p, within \p cap influences.
inline Influences merge_weights(WeightRule rule, const Eigen::Vector3d& p, const Eigen::Vector3d& p0,
                                const Influences& w0, const Eigen::Vector3d& p1, const Influences& w1, int cap) {
  const double d0 = (p - p0).norm(), d1 = (p - p1).norm();
  double c0, c1;  // shares of w0 and w1
  switch (rule) {
    case WeightRule::NearestEndpoint:
      c0 = d0 < d1 ? 1.0 : 0.0;
      break;
    case WeightRule::DistanceInterpolation:
      c0 = d0 + d1 > 0.0 ? 1.0 - d0 / (d0 + d1) : 0.5;
      break;
    case WeightRule::PowerSkinning: {
      const double D = d0 + d1, dinv = (D - d0) + (D - d1);
      c0 = dinv > 0.0 ? (D - d0) / dinv : 0.5;
      break;
    }
  }
  c1 = 1.0 - c0;
  InfluenceSum sum;
  if (c0 > 0.0) sum.add(w0, c0);
  if (c1 > 0.0) sum.add(w1, c1);
  return sum.keep_heaviest(cap);
}

}  // namespace OpenMeshSkinned
