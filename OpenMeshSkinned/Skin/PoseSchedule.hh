#pragma once
/** \file PoseSchedule.hh
 *  Which animation frames the decimater learns from (example poses) and which it is judged on
 *  (held-out frames, never used as examples).
 *
 *  Example times: K evenly spaced times over one clip, both ends included (time 0 when K = 1); with no
 *  clip chosen, K evenly spaced times over all clips laid end to end (in file order), both ends included.
 *  Held-out times: the midpoints between consecutive example times (the clip's middle when K = 1), plus,
 *  when one clip was chosen, four frames of every other clip at 1/8, 3/8, 5/8 and 7/8 of its length. At
 *  most max_held_out are kept, evenly thinned.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// A frame: clip index and time in seconds.
struct PoseTime {
  int clip = 0;
  double time = 0.0;
};

struct PoseSchedule {
  std::vector<PoseTime> examples;
  std::vector<PoseTime> held_out;
};

/// \p clip_index < 0 spreads the examples over all clips. Throws std::invalid_argument on k < 1, a clip
/// index out of range, or no clips.
PoseSchedule make_pose_schedule(const std::vector<Clip>& clips, int k, int clip_index, size_t max_held_out = 16);

/** For a frame animation (stored frames at \p frame_times, one clip): every example moved to the nearest
 *  stored frame, duplicates dropped; every held-out frame moved to the nearest stored frame that is not an
 *  example (dropped when there is none), duplicates dropped. So that the decimater learns from, and is
 *  judged on, frames that exist, never the blend between two. */
void snap_to_frames(PoseSchedule& s, const std::vector<double>& frame_times);

/// The poses at the given frames.
std::vector<Pose> poses_at(const Skeleton& skel, const std::vector<Clip>& clips, const std::vector<PoseTime>& times);

}  // namespace OpenMeshSkinned
