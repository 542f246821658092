#pragma once
// The example poses make_lods() decimates in and the held-out frames it judges in, chosen from the clips.

#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodProgress.hh>
#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** lod_pose_count(options, mesh) example times over the clips (or options.pose_clip), the bind pose unless
 *  !options.bind_pose, and the frames in between them held out; a frame animation's stored frames only (with
 *  few of them, half kept back). A mesh without clips is decimated and judged in its rest pose (a warning
 *  when \p poses_given). Says which in a message; throws IOError when a pose does not compose to finite
 *  matrices. \p name names the mesh in messages. */
LodPoses select_lod_poses(const SkinnedMesh& mesh, const LodOptions& options, const std::string& name = "the mesh",
                          const LodCallbacks& callbacks = {}, bool poses_given = false);

/// LodOptions::pose_select's values, "even" (the default) first.
const std::vector<std::string>& pose_selections();
/// pose_selections() as "even, motion, spread or ga", for messages.
std::string pose_selection_names();

/// \p v with \p precision decimals, fixed: the numbers in messages.
std::string fixed_number(double v, int precision);

}  // namespace OpenMeshSkinned
