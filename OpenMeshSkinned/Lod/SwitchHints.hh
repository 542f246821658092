#pragma once
/** \file SwitchHints.hh
 *  When an engine may switch to a LOD: the on-screen size below which its held-out Hausdorff error covers
 *  less than one pixel, in the terms engines set LOD thresholds in.
 *
 *  An object whose bounds span a fraction s of the screen height H (pixels) shows an error e (mesh units)
 *  over e * s * H / D pixels, D being the size the fraction is taken of; so the LOD holds the error under one
 *  pixel while s <= D / (e * H). The field of view does not enter: both engines measure s relative to the
 *  screen. Unity's LODGroup takes s of the bounds' largest side (its "relative screen height"), Unreal of the
 *  bounding sphere's diameter (its "screen size"; the sphere around the box, diameter = its diagonal).
 */

#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <string>
#include <utility>
#include <vector>

namespace OpenMeshSkinned {

/// The screen height the hints are computed for.
inline constexpr int kSwitchHintScreenHeight = 1080;

struct LodSwitchHint {
  /// Unity LODGroup: switch to the LOD below this relative screen height (at most 1: usable at any size).
  double unity_relative_height = 1.0;
  /// Unreal: switch to the LOD below this screen size (at most 1).
  double unreal_screen_size = 1.0;
};

/** The hint for a LOD of \p original whose held-out Hausdorff error is \p hausdorff_percent of the original's
 *  rest-pose bounding-box diagonal, on a screen \p screen_height pixels high. */
LodSwitchHint switch_hint(const SkinnedMesh& original, double hausdorff_percent,
                          int screen_height = kSwitchHintScreenHeight);

}  // namespace OpenMeshSkinned
