#pragma once
/** \file GltfValueCheck.hh
 *  Values in a glTF that assimp 5.2 would change without a word: non-finite and negative skin weights (its
 *  reader keeps only weights > 0, so the vertex silently follows fewer bones). We refuse them, as we do
 *  for every other format once assimp has read it.
 */

#include <string>

namespace OpenMeshSkinned {

/// Throws IOError ("<shown_as>: ...") naming the mesh, attribute and vertex when the .gltf/.glb
/// \p path has a non-finite or negative value in a WEIGHTS_n accessor. Does nothing for other formats
/// or files tinygltf cannot parse (the reader then reports the problem).
void check_gltf_weights(const std::string& path, const std::string& shown_as);

}  // namespace OpenMeshSkinned
