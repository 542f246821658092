#pragma once
/** \file CollapseLegality.hh
 *  OpenMesh's topological test of a collapse, answered in the caller's translation unit.
 *
 *  Debian builds OpenMesh with assertions on, and every status access inside the library checks its
 *  property's type name: TriConnectivity::is_collapse_ok builds and compares a std::string six times a
 *  call, much of LazyDecimaterT's run on the column (bench/README.md, "omsk-bench: the papers'
 *  workloads"). These functions give the same answers as
 *  TriConnectivity::is_collapse_ok and BaseDecimaterT::is_collapse_legal (test_collapse_legality checks
 *  them against the library on every halfedge through whole decimations), without the library's side
 *  effect of setting the "tagged" status bits of both one-rings.
 */

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <vector>

namespace OpenMeshSkinned {

/** TriConnectivity::is_collapse_ok: the edge and its ends exist, no triangle beside it has both other
 *  edges on the boundary, the one-rings of v0 and v1 share only the opposite vertices vl and vr, and an
 *  interior edge does not join two boundary vertices. */
template <typename Mesh>
bool link_condition_ok(const Mesh& mesh, typename Mesh::HalfedgeHandle v0v1) {
  using VertexHandle = typename Mesh::VertexHandle;
  using HalfedgeHandle = typename Mesh::HalfedgeHandle;
  if (mesh.status(mesh.edge_handle(v0v1)).deleted()) return false;
  const HalfedgeHandle v1v0 = mesh.opposite_halfedge_handle(v0v1);
  const VertexHandle v0 = mesh.to_vertex_handle(v1v0), v1 = mesh.to_vertex_handle(v0v1);
  if (mesh.status(v0).deleted() || mesh.status(v1).deleted()) return false;
  // The apex of the triangle on h's side (invalid on a boundary); false if the collapse would leave that
  // triangle's two other edges, both on the boundary, as a dangling pair.
  auto apex = [&](HalfedgeHandle h, VertexHandle& apex_vertex) {
    if (mesh.is_boundary(h)) return true;
    const HalfedgeHandle h1 = mesh.next_halfedge_handle(h), h2 = mesh.next_halfedge_handle(h1);
    apex_vertex = mesh.to_vertex_handle(h1);
    return !(mesh.is_boundary(mesh.opposite_halfedge_handle(h1)) &&
             mesh.is_boundary(mesh.opposite_halfedge_handle(h2)));
  };
  VertexHandle vl, vr;
  if (!apex(v0v1, vl) || !apex(v1v0, vr) || vl == vr) return false;
  thread_local std::vector<int> ring1;
  ring1.clear();
  for (const auto v : mesh.vv_range(v1)) ring1.push_back(v.idx());
  for (const auto v : mesh.vv_range(v0))
    if (v != vl && v != vr && std::find(ring1.begin(), ring1.end(), v.idx()) != ring1.end()) return false;
  return !(mesh.is_boundary(v0) && mesh.is_boundary(v1) && !mesh.is_boundary(v0v1) && !mesh.is_boundary(v1v0));
}

/** BaseDecimaterT::is_collapse_legal: v0 is not locked, link_condition_ok, the collapse does not leave a
 *  tetrahedron's faces folded onto each other (vl and vr joined, both of valence 3), a feature vertex
 *  moves only along a feature edge, a boundary vertex only along the boundary and not across a single
 *  triangle's interior, and v0 has at least two faces. */
template <typename Mesh>
bool collapse_legal(const Mesh& mesh, const OpenMesh::Decimater::CollapseInfoT<Mesh>& ci) {
  if (mesh.status(ci.v0).locked() || !link_condition_ok(mesh, ci.v0v1)) return false;
  if (ci.vl.is_valid() && ci.vr.is_valid()) {
    auto valence_is_3 = [&](typename Mesh::VertexHandle v) {
      int n = 0;
      for (auto it = mesh.cvoh_iter(v); it.is_valid() && n <= 3; ++it) ++n;
      return n == 3;
    };
    if (valence_is_3(ci.vl) && valence_is_3(ci.vr)) {
      for (const auto h : mesh.voh_range(ci.vl))
        if (mesh.to_vertex_handle(h) == ci.vr) return false;
    }
  }
  if (mesh.status(ci.v0).feature() && !mesh.status(mesh.edge_handle(ci.v0v1)).feature()) return false;
  if (mesh.is_boundary(ci.v0) && (!mesh.is_boundary(ci.v1) || (ci.vl.is_valid() && ci.vr.is_valid()))) return false;
  return mesh.cw_rotated_halfedge_handle(mesh.cw_rotated_halfedge_handle(ci.v0v1)) != ci.v0v1;
}

}  // namespace OpenMeshSkinned
