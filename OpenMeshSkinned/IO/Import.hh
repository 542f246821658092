#pragma once
/** \file Import.hh
 *  Reads any skinned asset assimp understands (glTF/GLB, FBX, Collada, X, MD5, B3D, SMD, ...) into one
 *  SkinnedMesh carrying its skeleton, skin, animation clips and materials.
 */

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/ImportOptions.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** Imports \p path into \p mesh (which is cleared first). Split vertices are welded by position and
 *  identical skin; normals and UVs become per-halfedge attributes so seams survive; each face keeps its
 *  material ("f:material") and each material its base-colour image (embedded, or read from beside the
 *  file). Morph targets become "v:morph_deltas", their weight animations clip channels.
 *
 *  Posing follows the glTF 2.0 rule whatever the format: a skinned vertex goes to sum_k w_k J_k O_k v,
 *  with J_k the joint node's world matrix (every ancestor, the scene root included) and O_k assimp's
 *  offset matrix; the skinned mesh's own node transform plays no part. Every mesh is stored in the space
 *  where it rests on screen, so the identity pose shows the character as a viewer does; a mesh without a
 *  skin is bound rigidly to its node (which becomes a joint). No example poses are set: the decimater
 *  modules need them (sample_poses_evenly over a clip, or use_bind_pose_only()).
 *  Throws IOError (missing, empty, unreadable or invalid file, or an unusable skin). */
ImportReport import_skinned(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt = {});

namespace detail {
/// import_skinned() after its checks, in this process: a glTF repaired or decoded into a private copy
/// (GltfRepair.hh) first, then import_scene().
ImportReport import_file(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt);
/// import_skinned() after its checks, in this process: reads \p read_path (a repaired copy, or \p path),
/// names \p path in errors and finds textures beside it.
ImportReport import_scene(const std::string& path, const std::string& read_path, SkinnedMesh& mesh,
                          const ImportOptions& opt);
}  // namespace detail

}  // namespace OpenMeshSkinned
