#pragma once
/** \file ExportParts.hh
 *  Steps of the glTF export: the mesh's primitives (one per material) and the animations. Internal to the
 *  exporter (ExportGltf.cc); the public entry point is export_gltf().
 */

#include "OpenMeshSkinned/IO/GltfBuffer.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

/** The mesh: per-corner vertices (a vertex splits where its normals or UVs do), normals recomputed from
 *  the geometry as it is now, skin weights in sets of four, morph targets. \p path names the file in errors. */
tinygltf::Mesh write_mesh(const SkinnedMesh& mesh, BufferWriter& buf, const std::string& path);

/// Whether the mesh is written with TEXCOORD_0 (the mesh's own UVs): when it has UVs, further UV sets or a texture.
bool writes_first_uv_set(const SkinnedMesh& mesh);

/** Where each UV set of the input goes: element s is the n of the TEXCOORD_n that carries the input's set
 *  s, -1 for a set the mesh does not have. Sets are numbered from 0 without gaps, as glTF requires. */
std::vector<int> written_uv_sets(const SkinnedMesh& mesh);

/** The written index of the input's UV set \p set: a set that is not written (a material that names a set
 *  no part of the input has) reads TEXCOORD_0, as the tangents for it are made from. */
int written_uv_index(const std::vector<int>& written, int set);

/// Every clip as a glTF animation of the joint nodes 0..J-1 and the morph weights of node \p mesh_node.
void write_clips(const SkinnedMesh& mesh, int mesh_node, BufferWriter& buf, tinygltf::Model& model);

}  // namespace OpenMeshSkinned::detail
