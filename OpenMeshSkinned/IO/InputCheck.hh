#pragma once
/** \file InputCheck.hh
 *  Every number a reader took from a file, checked in one place per kind before anything computes with it.
 *
 *  A corrupt key, transform or bind matrix would otherwise reach the solves, where a NaN never converges,
 *  or the written file, which the glTF validator then refuses. What has one obvious repair is repaired and
 *  said in one warning; the rest is refused with one IOError line "<file>: <object>: <value>".
 */

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Skin/Skeleton.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** Joints: rest transforms and inverse bind matrices finite, within float range (glTF stores floats),
 *  invertible (no zero scale), and affine (last row 0 0 0 1). Throws IOError naming the joint. */
void check_skeleton(const Skeleton& skel, const std::string& path);

/** One clip of a skeleton with \p n_targets morph targets.
 *
 *  Refused: a non-finite key time, a non-finite or out-of-float-range value, a rotation that is no
 *  quaternion (zero length), a channel of a joint or morph target that does not exist, a channel with
 *  more times than values. Repaired, with a warning each: keys out of time order (sorted); a clip whose
 *  first key lies before 0 (shifted to start at 0); keys that fall on one time once written as float
 *  seconds (merged, the later kept: glTF needs strictly increasing times); rotations that are not of unit
 *  length (renormalised); a non-finite duration or one shorter than the keys (set to the last key). */
void check_clip(Clip& clip, const Skeleton& skel, size_t n_targets, const std::string& path,
                std::vector<std::string>& warnings);

/// check_skeleton() and check_clip() on everything an importer put on \p mesh.
void check_input(SkinnedMesh& mesh, const std::string& path, std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned
