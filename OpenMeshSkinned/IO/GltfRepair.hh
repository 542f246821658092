#pragma once
/** \file GltfRepair.hh
 *  Valid glTF that assimp 5.2 cannot read, made readable before it gets there.
 *
 *  Today one case: a skin without "inverseBindMatrices". The spec makes them optional (identity by
 *  default), and assimp dereferences the missing accessor and crashes. The repair adds the identity
 *  matrices, so the file poses exactly as the spec says.
 */

#include <string>

namespace OpenMeshSkinned {

/** A repaired copy of a .gltf/.glb when it needs one, in a private temporary folder removed with the
 *  object; path() is "" when the file needs none (or is not glTF: the reader judges it). The files a
 *  .gltf refers to are linked into the folder under the same relative names. Throws IOError when the file
 *  needs a repair that cannot be made (a resource outside the file's folder). */
class RepairedGltf {
public:
  explicit RepairedGltf(const std::string& path);
  ~RepairedGltf();
  RepairedGltf(const RepairedGltf&) = delete;
  RepairedGltf& operator=(const RepairedGltf&) = delete;
  const std::string& path() const { return path_; }

private:
  std::string dir_, path_;
};

}  // namespace OpenMeshSkinned
