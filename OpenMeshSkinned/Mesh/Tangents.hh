#pragma once
/** \file Tangents.hh
 *  Tangent frames for normal maps, generated from the geometry, the normals and the normal map's UVs, in
 *  the manner of MikkTSpace (the frames glTF viewers assume when a file has none): per corner, the
 *  direction of increasing u in the corner's tangent plane, averaged over the corners that share a vertex,
 *  a normal, a UV and a handedness, with the handedness as the sign w.
 */

#include <Eigen/Core>

#include <vector>

namespace OpenMeshSkinned {

/// One triangle corner as the tangent generator sees it.
struct TangentCorner {
  int vertex = -1;           ///< corners of one vertex with equal normal, UV and handedness share a tangent
  Eigen::Vector3d position;  ///< the vertex's position
  Eigen::Vector3d normal;    ///< the corner's unit normal (the one written beside the tangent)
  /// The normal map's UV, origin bottom-left (v up, as the mesh carries UVs; the file's v is 1 - v).
  Eigen::Vector2d uv;
};

/** Tangents of \p corners, where corners 3t, 3t + 1, 3t + 2 are triangle t, counter-clockwise seen from
 *  its front. Returns one (x, y, z, w) per corner: xyz of unit length, orthogonal to the corner's normal,
 *  along increasing u; w = +1 when (normal x tangent) points along increasing v and -1 where the UVs are
 *  mirrored, so that the bitangent is w (normal x tangent) as glTF defines it.
 *
 *  Each triangle contributes, at each corner, the unit projection of its u direction onto the corner's
 *  tangent plane, weighted by the corner's angle. Corners of opposite handedness are never averaged
 *  together (a mirrored UV island's seam keeps two frames). A triangle without a frame of its own (zero
 *  area, or its UVs on a line) contributes nothing: its corners take their group's tangent, or else one
 *  of the same vertex and normal, or else any direction orthogonal to the normal with w = +1. */
std::vector<Eigen::Vector4d> corner_tangents(const std::vector<TangentCorner>& corners);

}  // namespace OpenMeshSkinned
