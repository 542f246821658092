#pragma once
/** \file ExportCorners.hh
 *  One corner of the mesh as a glTF vertex: which further UV and colour sets are written under which
 *  names, a corner's value in each, its normal recomputed from the geometry as it is now, its tangent
 *  frame's inputs and its weights in float. What write_mesh() (ExportMesh.cc) writes per corner; internal
 *  to the exporter.
 */

#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Mesh/Tangents.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

// One glTF vertex: an OpenMesh vertex with one wedge's normal, UV, further sets (CornerAttributes.hh) and
// tangent (zero in primitives without one).
struct Corner {
  int vertex;
  std::array<float, 3> n;
  std::array<float, 2> uv;
  std::vector<float> sets;  // each carried set's components, in corner_channels() order
  std::array<float, 4> tangent = {0, 0, 0, 0};
  bool operator<(const Corner& o) const {
    if (vertex != o.vertex) return vertex < o.vertex;
    if (n != o.n) return n < o.n;
    if (uv != o.uv) return uv < o.uv;
    if (sets != o.sets) return sets < o.sets;
    return tangent < o.tangent;
  }
};

// A carried set as written: its attribute name and how many components each vertex has.
struct Written {
  CornerChannel channel;
  std::string attribute;
  int components;
};

/** TEXCOORD_n and COLOR_n must be numbered 0, 1, ... without gaps: sets are renumbered in order (UV sets
 *  from \p first_uv, after TEXCOORD_0 when it is written). Colours are VEC4, or VEC3 when every alpha is 1
 *  (as assimp reports RGB colours), which says the same thing in less space. */
std::vector<Written> written_sets(const SkinnedMesh& mesh, int first_uv);

/** A set's value as written: UVs flipped to glTF's top-left origin like TEXCOORD_0, colours within [0, 1]
 *  (interpolation can round a hair past 1), anything non-finite as the set's fallback. */
void append_set(const Written& w, OpenMesh::Vec4f x, std::vector<float>& out);

/// Weights in float, made to sum to one in float as glTF validators check it.
void float_weights(const Influences& inf, int slots, std::vector<uint16_t>& joints, std::vector<float>& weights);

/** The normal of a corner, recomputed from the geometry as it is now (a LOD's vertices have moved): the
 *  area-weighted normals of the faces around the vertex whose corner carries a stored normal within 60
 *  degrees of this corner's, so hard edges and normal seams of the input stay hard. \p point gives each
 *  vertex's position: the rest position, or a morph target's. */
template <typename PointOf>
Eigen::Vector3d corner_normal(const SkinnedMesh& mesh, SkinnedMesh::HalfedgeHandle heh, const PointOf& point) {
  const auto stored = mesh.normal(heh);
  const Eigen::Vector3d ref(stored[0], stored[1], stored[2]);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto h : mesh.vih_range(mesh.to_vertex_handle(heh))) {
    if (mesh.is_boundary(h)) continue;
    const auto other = mesh.normal(h);
    const Eigen::Vector3d o(other[0], other[1], other[2]);
    if (ref.norm() > 0.0 && o.norm() > 0.0 && o.dot(ref) < kHardEdgeNormalCos * o.norm() * ref.norm()) continue;
    // The cross product is the face normal scaled by twice the area: area weighting without normalising
    // a degenerate face's zero vector (which gives NaN).
    const SkinnedMesh::Point p0 = point(mesh.from_vertex_handle(h)), p1 = point(mesh.to_vertex_handle(h)),
                             p2 = point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    const auto c = (p1 - p0) % (p2 - p0);
    sum += Eigen::Vector3d(c[0], c[1], c[2]);
  }
  const double len = sum.norm();
  if (len > 0.0 && std::isfinite(len)) return sum / len;
  const double rlen = ref.norm();
  return rlen > 0.0 && std::isfinite(rlen) ? Eigen::Vector3d(ref / rlen) : Eigen::Vector3d(0.0, 0.0, 1.0);
}

/** The normal map's UVs of a primitive's corners (the input's UV set \p set, origin bottom-left as the mesh
 *  keeps them), their written normals and positions, as the tangent generator takes them. */
std::vector<TangentCorner> tangent_corners(const SkinnedMesh& mesh,
                                           const std::vector<SkinnedMesh::HalfedgeHandle>& hehs,
                                           const std::vector<Eigen::Vector3d>& normals, int set);

}  // namespace OpenMeshSkinned::detail
