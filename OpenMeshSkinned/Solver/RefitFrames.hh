#pragma once
/** \file RefitFrames.hh
 *  The final fit for a mesh animated without a skeleton (a frame animation: the rest shape and one morph
 *  target per stored frame, FrameAnimation.hh): every stored frame's LOD shape fitted on its own to the
 *  original's shape in that frame (refit_positions in that one pose), then written back as the rest shape
 *  and the targets' offsets. The clip plays the linear blend of the two stored frames around any time, in
 *  the original as in the LOD, so frames fitted one by one are what every time between them blends.
 *
 *  The example poses' fit moves the rest shape, which moves every frame alike; a frame's own shape can only
 *  be fitted through its own offsets.
 */

#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"
#include "OpenMeshSkinned/Solver/Refit.hh"

namespace OpenMeshSkinned {

struct RefitFramesReport {
  size_t frames = 0;  ///< stored frames fitted (0: not a frame animation, nothing changed)
};

/** Fits every stored frame of \p lod (a decimation of \p original) as refit_positions() does in one pose,
 *  with \p settings (its skin step aside). Does nothing unless every morph target of \p lod is played alone at
 *  weight 1 at some key of its clips (a frame animation). */
RefitFramesReport refit_frames(SkinnedMesh& lod, const SkinnedMesh& original, const RefitSettings& settings = {});

}  // namespace OpenMeshSkinned
