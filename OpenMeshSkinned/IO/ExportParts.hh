#pragma once
/** \file ExportParts.hh
 *  Steps of the glTF export: the mesh's primitives (one per material) and the animations. Internal to the
 *  exporter (ExportGltf.cc); the public entry point is export_gltf().
 */

#include "OpenMeshSkinned/IO/GltfBuffer.hh"
#include "OpenMeshSkinned/Mesh/SkinnedMesh.hh"

#include <string>

namespace OpenMeshSkinned::detail {

/** The mesh: per-corner vertices (a vertex splits where its normals or UVs do), normals recomputed from
 *  the geometry as it is now, skin weights in sets of four, morph targets. \p path names the file in errors. */
tinygltf::Mesh write_mesh(const SkinnedMesh& mesh, BufferWriter& buf, const std::string& path);

/// Every clip as a glTF animation of the joint nodes 0..J-1 and the morph weights of node \p mesh_node.
void write_clips(const SkinnedMesh& mesh, int mesh_node, BufferWriter& buf, tinygltf::Model& model);

}  // namespace OpenMeshSkinned::detail
