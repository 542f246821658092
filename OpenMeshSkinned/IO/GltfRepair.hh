#pragma once
/** \file GltfRepair.hh
 *  Valid glTF that assimp 5.2 cannot read, made readable before it gets there.
 *
 *  - A skin without "inverseBindMatrices": the spec makes them optional (identity by default), and
 *    assimp dereferences the missing accessor and crashes. The repair adds the identity matrices, so the
 *    file poses exactly as the spec says.
 *  - Compressed and quantised data (`EXT_meshopt_compression`, `KHR_meshopt_compression` version 0,
 *    `KHR_draco_mesh_compression`, `KHR_mesh_quantization`): decoded into plain buffer views
 *    (GltfDecompress.hh). `KHR_texture_basisu` images pass through untouched.
 *  - A GLB without a binary chunk (every buffer a URI), whose first buffer assimp takes for the missing
 *    chunk: the copy is a .gltf.
 *  - STEP and CUBICSPLINE animation samplers, which assimp reads as LINEAR ones: rewritten as LINEAR keys
 *    that pose the same (GltfInterpolation.hh).
 *  A file that requires any other extension the tool cannot honour is refused.
 */

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** A repaired copy of a .gltf/.glb when it needs one, in a private temporary folder removed with the
 *  object; path() is "" when the file needs none (or is not glTF: the reader judges it). The files a
 *  glTF refers to are linked into the folder under the same relative names; decoded data goes into the
 *  GLB's binary chunk, or into a file of its own beside a .gltf. Throws IOError, naming \p path, when the
 *  file requires an extension the tool cannot honour, when its compressed data cannot be decoded, or
 *  when it needs a repair that cannot be made (a buffer outside the file's folder; images there are
 *  read beside the file by the material reader, not through the copy). */
class RepairedGltf {
public:
  explicit RepairedGltf(const std::string& path);
  ~RepairedGltf();
  RepairedGltf(const RepairedGltf&) = delete;
  RepairedGltf& operator=(const RepairedGltf&) = delete;
  const std::string& path() const { return path_; }
  /// What the copy keeps differently from the file, one line each for the user (a STEP sampler as LINEAR keys).
  const std::vector<std::string>& notes() const { return notes_; }

private:
  std::string dir_, path_;
  std::vector<std::string> notes_;
};

}  // namespace OpenMeshSkinned
