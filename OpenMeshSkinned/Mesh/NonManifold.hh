#pragma once
/** \file NonManifold.hh
 *  Making a triangle soup fit OpenMesh's halfedge structure without dropping a face: vertices where
 *  several face fans meet get a copy per extra fan, as OpenMesh's own readers do for complex edges.
 */

#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <OpenMesh/Core/Utils/Property.hh>

#include <cstddef>

namespace OpenMeshSkinned {

/// A new vertex with \p vh's position, skin ("v:skin_influences") and morph offsets.
SkinnedMesh::VertexHandle copy_vertex(SkinnedMesh& mesh, SkinnedMesh::VertexHandle vh);

/** Gives every vertex where several face fans meet one copy per extra fan (OpenMesh accepts such a vertex,
 *  but its circulators see one fan only and the decimater would treat it as a boundary). Faces keep their
 *  corner normals, UVs and material (\p h_fmat). Returns the number of copies. */
size_t split_nonmanifold_vertices(SkinnedMesh& mesh, OpenMesh::FPropHandleT<int> h_fmat);

}  // namespace OpenMeshSkinned
