#pragma once
/** \file LoopSubdivision.hh
 *  Loop subdivision of a skinned mesh in which the skin weights are refined with exactly the same masks as
 *  the positions, so a subdivided character deforms like a smoothed version of the original. Used to build
 *  the papers' dense workloads from real characters. Per-halfedge normals and UVs are not carried.
 */

#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

namespace OpenMeshSkinned {

/// One Loop step: 4x the triangles. Weights beyond Influences::kCapacity keep the heaviest, renormalised.
SkinnedMesh loop_subdivide(const SkinnedMesh& mesh);

}  // namespace OpenMeshSkinned
