#pragma once
/** \file ImportFrames.hh
 *  Meshes animated without a skeleton, read as a frame animation (Skin/FrameAnimation.hh): every stored
 *  frame of a Quake MD2/MD3/MDL file, or every file of a numbered sequence (walk_0001.obj, walk_0002.obj,
 *  ...; any format assimp reads), the same mesh in each.
 */

#include "OpenMeshSkinned/IO/ImportOptions.hh"
#include "OpenMeshSkinned/IO/StoredFrames.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** Reads a frame animation into \p mesh: the stored frames of \p files[0] when it is the only file, else
 *  one frame per file. Each frame is read like import_skinned() (materials, textures and UVs come from
 *  the first) and must give the same vertices and faces; frame f plays at time f / fps. When every frame
 *  has frame 0's shape the mesh is read as a still one (no clip) and the report says so. Throws IOError
 *  naming the first frame that does not match, and when there is only one frame. */
ImportReport import_frame_animation(const std::vector<std::string>& files, SkinnedMesh& mesh, const ImportOptions& opt,
                                    double fps);

}  // namespace OpenMeshSkinned
