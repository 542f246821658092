#include "OpenMeshSkinned/Mesh/LoopSubdivision.hh"

#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace OpenMeshSkinned {
namespace {

// A position and a skin, blended with the same weights.
struct Blend {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  InfluenceSum w;

  void add(double c, const Eigen::Vector3d& q, const Influences& inf) {
    p += c * q;
    w.add(inf, c);
  }
  Influences influences() const { return w.keep_heaviest(Influences::kCapacity); }
};

}  // namespace

SkinnedMesh loop_subdivide(const SkinnedMesh& in) {
  const auto hi = influences_handle(in);
  const auto hfm = face_material_handle(in);
  SkinnedMesh out;
  request_skinned_attributes(out);
  const auto ho = add_skin(out);
  const auto hom = face_material_handle(out);
  skeleton(out) = skeleton(in);
  example_poses(out) = example_poses(in);
  clips(out) = clips(in);
  materials(out) = materials(in);

  auto pos = [&](SkinnedMesh::VertexHandle v) {
    return Eigen::Vector3d(in.point(v)[0], in.point(v)[1], in.point(v)[2]);
  };
  std::vector<SkinnedMesh::VertexHandle> vmap(in.n_vertices());
  for (auto v : in.vertices()) {
    Blend b;
    if (in.is_boundary(v)) {
      // Boundary rule: 3/4 the vertex, 1/8 each boundary neighbour.
      b.add(0.75, pos(v), in.property(hi, v));
      for (auto h : in.voh_range(v)) {
        const bool border = in.is_boundary(h) || in.is_boundary(in.opposite_halfedge_handle(h));
        if (border) b.add(0.125, pos(in.to_vertex_handle(h)), in.property(hi, in.to_vertex_handle(h)));
      }
    } else {
      const int n = static_cast<int>(in.valence(v));
      const double beta = n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
      b.add(1.0 - n * beta, pos(v), in.property(hi, v));
      for (auto u : in.vv_range(v)) b.add(beta, pos(u), in.property(hi, u));
    }
    vmap[v.idx()] = out.add_vertex(SkinnedMesh::Point(b.p.x(), b.p.y(), b.p.z()));
    out.property(ho, vmap[v.idx()]) = b.influences();
  }
  std::vector<SkinnedMesh::VertexHandle> emap(in.n_edges());
  for (auto e : in.edges()) {
    const auto h = in.halfedge_handle(e, 0), o = in.halfedge_handle(e, 1);
    const auto a = in.to_vertex_handle(h), c = in.to_vertex_handle(o);
    Blend b;
    if (in.is_boundary(e)) {
      b.add(0.5, pos(a), in.property(hi, a));
      b.add(0.5, pos(c), in.property(hi, c));
    } else {
      const auto l = in.to_vertex_handle(in.next_halfedge_handle(h)),
                 r = in.to_vertex_handle(in.next_halfedge_handle(o));
      b.add(0.375, pos(a), in.property(hi, a));
      b.add(0.375, pos(c), in.property(hi, c));
      b.add(0.125, pos(l), in.property(hi, l));
      b.add(0.125, pos(r), in.property(hi, r));
    }
    emap[e.idx()] = out.add_vertex(SkinnedMesh::Point(b.p.x(), b.p.y(), b.p.z()));
    out.property(ho, emap[e.idx()]) = b.influences();
  }
  for (auto f : in.faces()) {
    SkinnedMesh::VertexHandle v[3], m[3];
    int k = 0;
    for (auto h : in.fh_range(f)) {
      v[k] = vmap[in.to_vertex_handle(h).idx()];
      m[k] = emap[in.edge_handle(in.next_halfedge_handle(h)).idx()];  // edge after corner k
      ++k;
    }
    const int mat = in.property(hfm, f);
    // Corner k sits between the edge before it (m[k-1]) and the edge after it (m[k]).
    for (int c = 0; c < 3; ++c) out.property(hom, out.add_face(v[c], m[c], m[(c + 2) % 3])) = mat;
    out.property(hom, out.add_face(m[0], m[1], m[2])) = mat;
  }
  out.update_face_normals();
  clear_corner_attributes(out);
  return out;
}

}  // namespace OpenMeshSkinned
