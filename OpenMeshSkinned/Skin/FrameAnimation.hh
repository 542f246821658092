#pragma once
/** \file FrameAnimation.hh
 *  A mesh animated without a skeleton: one connectivity, F stored frames of positions (Quake MD2/MD3,
 *  a numbered OBJ sequence, a cloth or face cache). It is kept in the form glTF plays: frame 0 is the rest
 *  shape, every later frame f a morph target "frame_000f" (its offsets from frame 0), and one clip whose
 *  weight channels reach 1 on target f at frame f's time and fall linearly to 0 at its neighbours' times,
 *  so that any time plays the linear blend of the two frames around it. The frame times are kept in the
 *  named mesh property "m:frame_times" (seconds): its presence says that the mesh is a frame animation.
 *
 *  The decimater and every exporter then treat it like any mesh with morph targets: collapses carry the
 *  offsets (MorphTransferT), the glTF file animates them, the poses of the clip pose it.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

namespace prop_names {
inline constexpr const char* kFrameTimes = "m:frame_times";
}  // namespace prop_names

/// Positions of every vertex (by index) in one frame.
using FramePositions = std::vector<Eigen::Vector3d>;

/** Turns \p mesh (whose points are frame 0) into a frame animation of \p frames (frames[0] included, each
 *  with mesh.n_vertices() positions) at \p times (seconds, increasing), played by a clip named
 *  \p clip_name. Existing morph targets and clips are replaced. Throws std::invalid_argument on sizes that
 *  do not match or times that do not increase. */
void set_frame_animation(SkinnedMesh& mesh, const std::vector<FramePositions>& frames, const std::vector<double>& times,
                         const std::string& clip_name = "frames");

/** Makes \p mesh, whose morph targets are frames 1 .. F-1 (F = times.size()) and whose points are frame 0,
 *  a frame animation: the clip and the times. Throws std::invalid_argument as set_frame_animation(). */
void set_frame_times(SkinnedMesh& mesh, const std::vector<double>& times, const std::string& clip_name = "frames");

/// The stored frames' times; empty when \p mesh is not a frame animation.
const std::vector<double>& frame_times(const SkinnedMesh& mesh);

/// The positions of every vertex in stored frame \p f of a frame animation (morph offsets applied).
FramePositions frame_positions(const SkinnedMesh& mesh, size_t f);

/// The frame animation's clip (the one set_frame_animation made); -1 when there is none.
int frame_clip(const SkinnedMesh& mesh);

/** Keeps only the stored frames \p keep (sorted, frame 0 among them) as morph targets and clip keys: the
 *  frames in between are then played as the linear blend of the kept ones around them (key-frame
 *  extraction). The rest shape stays frame 0. */
void keep_frames(SkinnedMesh& mesh, const std::vector<size_t>& keep);

/** A skinned clip baked into a frame animation: \p mesh posed at \p n_frames evenly spaced times of clip
 *  \p clip (both ends included), every vertex then bound rigidly to joint 0, which no clip moves. The
 *  skeleton and materials stay; the other clips go. For analysing skinned characters as frames (and for
 *  tests: a skinned tube is an articulated animation whose parts are known). */
SkinnedMesh bake_frame_animation(const SkinnedMesh& mesh, size_t clip, size_t n_frames);

}  // namespace OpenMeshSkinned
