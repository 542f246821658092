#pragma once
/** \file GltfValueCheck.hh
 *  Values in a glTF that assimp 5.2 would change without a word: non-finite and negative skin weights (its
 *  reader keeps only weights > 0, so the vertex silently follows fewer bones), joint indices outside the
 *  skin (dropped, the rest rescaled), and skin accessors that claim more elements than their buffer view
 *  holds; sparse accessors' substitutes included, whose indices must lie inside their accessor (the
 *  reader patches them in place), for POSITION too. We refuse them, as we do for every other format once
 *  assimp has read it (InputCheck.hh).
 */

#include <string>

namespace OpenMeshSkinned {

/** Throws IOError ("<shown_as>: ...") when the .gltf/.glb \p path has, in a primitive's JOINTS_n or
 *  WEIGHTS_n: an accessor reaching past its buffer view (or the view past its buffer), a non-finite or
 *  negative weight, or a weighted joint index outside the skin of a node that uses the mesh, in its base
 *  data or its sparse substitutes; or, there and in POSITION, sparse indices outside the accessor or not
 *  increasing, or sparse indices or values reaching past their views. The message names the accessor, or
 *  the mesh, attribute and vertex. Does nothing for other formats or files
 *  tinygltf cannot parse (the reader then reports the problem). */
void check_gltf_values(const std::string& path, const std::string& shown_as);

}  // namespace OpenMeshSkinned
