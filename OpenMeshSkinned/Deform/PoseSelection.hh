#pragma once
/** \file PoseSelection.hh
 *  Choosing the example poses the decimater learns from among the frames that are not held out, instead of
 *  at even times: evenly over the motion, farthest first, or by the report's key-frame GA (the K frames from
 *  which linear interpolation rebuilds all the others best). Works on frame animations and on skinned clips
 *  alike (frames are vertex positions, morph offsets and skin applied). Motion is measured on the posed
 *  positions, so a root that travels counts as much as a limb that bends; every candidate frame is held at once
 *  (at most max_vertices points each).
 */

#include "OpenMeshSkinned/Deform/KeyframeGA.hh"
#include "OpenMeshSkinned/Skin/PoseSchedule.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <vector>

namespace OpenMeshSkinned {

/** The frames to choose from: every stored frame of a frame animation, or every clip sampled \p fps times
 *  a second (both ends included), laid end to end in clip order; frames within half a step of a
 *  \p held_out frame are left out, so that the held-out frames stay unseen. With \p clip >= 0, that clip's
 *  frames only. */
std::vector<PoseTime> candidate_frames(const SkinnedMesh& mesh, const std::vector<PoseTime>& held_out, int clip = -1,
                                       double fps = 30.0);

/** \p k of the \p candidates (k >= 2: the first and the last are always among them) chosen by
 *  select_keyframes_ga() on the posed positions of at most \p max_vertices vertices (evenly strided: the
 *  fitness needs the motion, not every vertex). Times are taken as laid end to end, so a clip's last frame
 *  and the next clip's first count as neighbours. */
std::vector<PoseTime> select_poses_ga(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                      size_t max_vertices = 2000, const KeyframeGaSettings& settings = {});

/** \p k of the \p candidates chosen farthest first: each the frame whose posed positions (of at most
 *  \p max_vertices vertices, evenly strided) lie farthest, in the sum of squared distances, from every frame chosen
 *  before it and, with \p from_bind_pose (the bind pose is an example too), from the bind pose; without it the
 *  first candidate is chosen first. Evenly spaced times give each clip examples by its length, so a short, violent
 *  clip (a run beside a long walk) gets few and its deepest bends none; this covers the bends wherever they are.
 *  In candidate order. Throws std::invalid_argument on no candidates. */
std::vector<PoseTime> select_poses_spread(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                          bool from_bind_pose = true, size_t max_vertices = 2000);

/** \p k of the \p candidates evenly spaced over the motion: along the candidates in order, each step between two
 *  frames of one clip counts how far the posed positions move (root of the summed squares, at most \p max_vertices
 *  vertices, evenly strided), and the frames nearest to k evenly spaced points of that length, both ends
 *  included, are taken. Even times give each clip examples by its length; this gives them by how far the mesh
 *  moves, so a short, fast clip beside a long, slow one (a run beside a walk) gets its share. In candidate order.
 *  Throws std::invalid_argument on no candidates. */
std::vector<PoseTime> select_poses_by_motion(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                             size_t max_vertices = 2000);

}  // namespace OpenMeshSkinned
