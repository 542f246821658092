#pragma once
/** \file LodAreaExponent.hh
 *  Which power of the area the tool's skinned and frames priorities divide by (LodOptions::area_exponent,
 *  ModSkinnedQuadricT::set_area_exponent, ModFrameQuadricT::set_area_exponent) when the options leave it to
 *  the input.
 */

#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodPoseCount.hh>

#include <cstddef>

namespace OpenMeshSkinned {

/// LodOptions::area_exponent's value that leaves the power to lod_area_exponent() (the default).
constexpr double kAutoAreaExponent = -1.0;

/** options.area_exponent when it is set (not kAutoAreaExponent). Otherwise 0.5 for a mesh of at most
 *  kSmallMeshVertices vertices and 1 (per area) above. Why: on coarse inputs the square root lowers the held-out
 *  RMS of every level against per area; on dense ones (Testwuson subdivided to 60k and 240k triangles) it
 *  raised it at the coarse levels (bench/README.md, "Defaults chosen by measurement"). */
inline double lod_area_exponent(const LodOptions& options, size_t n_vertices) {
  if (options.area_exponent != kAutoAreaExponent) return options.area_exponent;
  return n_vertices <= kSmallMeshVertices ? 0.5 : 1.0;
}

/** For the frames method (meshes animated without a skeleton): options.area_exponent when it is set;
 *  otherwise 0.25 when the coarsest level keeps at most half of the input's triangles (\p coarsest_kept, a
 *  fraction), and 0 (the energy) above. Why: on the MD2 characters a quarter power lowered the held-out RMS
 *  and Hausdorff of the 50, 25 and 10 % levels against the energy, and raised the RMS of light levels, where
 *  a few collapses are made at near-zero error (bench/README.md, "Defaults chosen by measurement"). */
inline double lod_frames_area_exponent(const LodOptions& options, double coarsest_kept) {
  if (options.area_exponent != kAutoAreaExponent) return options.area_exponent;
  return coarsest_kept <= 0.5 ? 0.25 : 0.0;
}

}  // namespace OpenMeshSkinned
