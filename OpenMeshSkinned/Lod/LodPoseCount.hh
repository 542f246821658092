#pragma once
// How many example poses make_lods() learns from when LodOptions::poses leaves it to the mesh.

#include <OpenMeshSkinned/Lod/LodOptions.hh>

#include <cstddef>
#include <string>

namespace OpenMeshSkinned {

/// LodOptions::poses's value that leaves the count to lod_pose_count() (the default).
constexpr int kAutoLodPoses = 0;
/// Example poses per clip that moves joints, and the count for every other mesh.
constexpr int kLodPosesPerClip = 8;
/// The most lod_pose_count() chooses.
constexpr int kMaxAutoLodPoses = 16;
/// Up to this many vertices a mesh gets kLodPosesPerClip for each of its clips; above, kLodPosesPerClip in all.
constexpr size_t kSmallMeshVertices = 20000;

/** options.poses when it is set (not kAutoLodPoses). Otherwise, for a mesh of at most kSmallMeshVertices
 *  vertices, kLodPosesPerClip for each clip that moves joints (one when options.pose_clip names one), at most
 *  kMaxAutoLodPoses; kLodPosesPerClip for the rest (larger meshes, morph-only and frame animations, no clip).
 *  Why: the example times are spread evenly over the clips end to end, so a short clip beside a long one gets
 *  one or two, and a bend of it that no example shows becomes a small LOD's worst held-out error (each of its
 *  few triangles carries much of the outline). More poses cost time and memory in proportion to the mesh, so
 *  only small meshes get them; a frame animation learns from stored frames, and more of them measured worse
 *  there (bench/README, "Held-out error against gltfpack"). */
int lod_pose_count(const LodOptions& options, const SkinnedMesh& mesh);

/// lod_pose_count()'s rule in a few words, for help texts.
std::string lod_pose_count_rule();

}  // namespace OpenMeshSkinned
