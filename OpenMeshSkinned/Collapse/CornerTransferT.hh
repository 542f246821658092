#pragma once
/** \file CornerTransferT.hh
 *  Per-corner attributes of a vertex that a collapse moved: the first UV set (the mesh's texcoords) and
 *  every set CornerAttributes.hh carries (further UV sets, colours). After a collapse v1's corners hold
 *  stale values (v0's, or v1's at a position v1 has left): each corner is re-interpolated, set by set, in
 *  the faces around the collapse as they were, restricted to the faces of the corner's chart in that set,
 *  at the closest point of the closest such face. The chart is what keeps a seam a seam: a corner on one
 *  side of a UV seam must not take coordinates from the other side's island, nor a corner on one side of
 *  a colour boundary the other side's colour. Each set has its own charts, as each has its own seams.
 *
 *  The collapse also moves halfedges between faces: where the collapsed edge's two triangles vanish, the
 *  surviving halfedge of each takes the place of its neighbour's in the face beyond, carrying the vanished
 *  triangle's value for the far vertex. Across a seam that is the other side's value; apply() puts back
 *  what every surviving face had at its other corners, for the carried sets. UV0 is left as the collapse
 *  leaves it, as it always was: putting it back too changes existing LODs' UVs (some of Testwuson's corners
 *  at half the triangles), a change to be judged on textured characters of its own.
 *
 *  Usage, around each collapse: record() before, apply() after. Does nothing on a mesh that carries no
 *  set (UV0 counts only when some corner is non-zero, as generated meshes carry it all zero), so it costs
 *  nothing there.
 */

#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"

#include <cmath>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class CornerTransferT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using HalfedgeHandle = typename Mesh::HalfedgeHandle;

  explicit CornerTransferT(Mesh& mesh) : mesh_(mesh) {}

  /// Looks for sets to keep; call once before decimating (and again if the mesh gains sets).
  void prepare() {
    uv0_ = false;
    if (mesh_.has_halfedge_texcoords2D())
      // Corners only: a border halfedge belongs to no face, and nothing sets (or reads) its UV, which may
      // hold anything; counting it made a UV-less 1M-triangle grid pay for UV bookkeeping (bench/README.md,
      // "omsk-bench: the papers' workloads").
      for (auto h : mesh_.halfedges())
        if (!mesh_.is_boundary(h) && (mesh_.texcoord2D(h)[0] != 0 || mesh_.texcoord2D(h)[1] != 0)) {
          uv0_ = true;
          break;
        }
    channels_ = corner_channels(mesh_);
    n_ = (uv0_ ? 1 : 0) + channels_.size();
  }
  bool active() const { return n_ > 0; }

  /// Remembers the faces around \p v0 and \p v1 with their corners' positions and values.
  void record(VertexHandle v0, VertexHandle v1) {
    sources_.clear();
    values_.clear();
    kept_.clear();
    kept_values_.clear();
    if (n_ == 0) return;
    for (const VertexHandle c : {v0, v1})
      for (auto fh : mesh_.vf_range(c)) {
        Source s;
        int k = 0;
        for (auto h : mesh_.fh_range(fh)) {
          s.p[k] = to_eigen(mesh_.point(mesh_.to_vertex_handle(h)));
          s.v[k] = mesh_.to_vertex_handle(h).idx();
          for (size_t ch = 0; ch < n_; ++ch) values_.push_back(get(ch, h));
          const VertexHandle to = mesh_.to_vertex_handle(h);
          if (!channels_.empty() && to != v0 && to != v1) {
            kept_.push_back({fh.idx(), to.idx()});
            for (size_t ch = 0; ch < n_; ++ch) kept_values_.push_back(get(ch, h));
          }
          ++k;
        }
        sources_.push_back(s);
      }
  }

  /// Sets the values of \p v1's corners from the recorded faces at its current position. Call after the collapse.
  void apply(VertexHandle v1) {
    if (sources_.empty() || (uv0_ && !mesh_.has_halfedge_texcoords2D())) return;
    const Eigen::Vector3d p = to_eigen(mesh_.point(v1));
    const size_t ns = sources_.size();
    dist_.resize(ns);
    bary_.resize(ns);
    for (size_t i = 0; i < ns; ++i) dist_[i] = closest_barycentric(sources_[i].p, p, bary_[i]);
    for (auto h : mesh_.vih_range(v1)) {
      if (mesh_.is_boundary(h)) continue;
      const auto hb = mesh_.next_halfedge_handle(h), hc = mesh_.next_halfedge_handle(hb);
      for (const HalfedgeHandle o : {hb, hc}) restore(mesh_.face_handle(h).idx(), o);
      for (size_t ch = 0; ch < n_; ++ch) {
        mark_chart(ch, mesh_.to_vertex_handle(hb).idx(), get(ch, hb), mesh_.to_vertex_handle(hc).idx(), get(ch, hc));
        double best = HUGE_VAL;
        Eigen::Vector4d x;
        for (size_t i = 0; i < ns; ++i) {
          if (!in_chart_[i] || !(dist_[i] < best)) continue;
          best = dist_[i];
          const Eigen::Vector3d& b = bary_[i];
          x = b[0] * value(i, 0, ch) + b[1] * value(i, 1, ch) + b[2] * value(i, 2, ch);
        }
        if (best < HUGE_VAL) set(ch, h, x);
      }
    }
  }

private:
  struct Source {
    Eigen::Vector3d p[3];
    int v[3];
  };
  struct Kept {
    int face, vertex;
  };

  // Set 0 is UV0 when the mesh has it; the carried sets follow.
  Eigen::Vector4d get(size_t ch, HalfedgeHandle h) const {
    if (uv0_ && ch == 0) {
      const auto t = mesh_.texcoord2D(h);
      return Eigen::Vector4d(t[0], t[1], 0.0, 0.0);
    }
    const OpenMesh::Vec4f& t = mesh_.property(channels_[ch - (uv0_ ? 1 : 0)].handle, h);
    return Eigen::Vector4d(t[0], t[1], t[2], t[3]);
  }
  void set(size_t ch, HalfedgeHandle h, const Eigen::Vector4d& x) {
    if (uv0_ && ch == 0)
      mesh_.set_texcoord2D(h, typename Mesh::TexCoord2D(x[0], x[1]));
    else
      mesh_.property(channels_[ch - (uv0_ ? 1 : 0)].handle, h) = OpenMesh::Vec4f(x[0], x[1], x[2], x[3]);
  }
  // The value face \p face had at the corner \p o now is (whose halfedge the collapse may have replaced).
  void restore(int face, HalfedgeHandle o) {
    const int to = mesh_.to_vertex_handle(o).idx();
    for (size_t i = 0; i < kept_.size(); ++i)
      if (kept_[i].face == face && kept_[i].vertex == to) {
        for (size_t ch = uv0_ ? 1 : 0; ch < n_; ++ch) set(ch, o, kept_values_[i * n_ + ch]);
        return;
      }
  }

  const Eigen::Vector4d& value(size_t source, int corner, size_t ch) const {
    return values_[(3 * source + corner) * n_ + ch];
  }

  static bool same(const Eigen::Vector4d& x, const Eigen::Vector4d& y) { return (x - y).norm() < kSeamUvTolerance; }

  // The chart of a corner whose other two vertices are b and c, in set ch: the source faces that give b or
  // c the corner's value, grown across edges whose two ends carry the same values on both sides (no seam).
  void mark_chart(size_t ch, int b, const Eigen::Vector4d& tb, int c, const Eigen::Vector4d& tc) {
    const size_t ns = sources_.size();
    in_chart_.assign(ns, 0);
    for (size_t i = 0; i < ns; ++i)
      for (int k = 0; k < 3; ++k) {
        const Source& s = sources_[i];
        if ((s.v[k] == b && same(value(i, k, ch), tb)) || (s.v[k] == c && same(value(i, k, ch), tc))) in_chart_[i] = 1;
      }
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t i = 0; i < ns; ++i) {
        if (in_chart_[i]) continue;
        for (size_t j = 0; j < ns && !in_chart_[i]; ++j) {
          if (!in_chart_[j]) continue;
          int shared = 0;
          for (int a = 0; a < 3; ++a)
            for (int d = 0; d < 3; ++d)
              shared += sources_[i].v[a] == sources_[j].v[d] && same(value(i, a, ch), value(j, d, ch));
          if (shared >= 2) in_chart_[i] = grew = 1;
        }
      }
    }
  }

  Mesh& mesh_;
  bool uv0_ = false;
  std::vector<CornerChannel> channels_;
  size_t n_ = 0;
  std::vector<Source> sources_;
  std::vector<Eigen::Vector4d> values_;  // per source, per corner, per set
  std::vector<Kept> kept_;               // the surviving faces' corners of other vertices than v0 and v1
  std::vector<Eigen::Vector4d> kept_values_;
  std::vector<double> dist_;
  std::vector<Eigen::Vector3d> bary_;
  std::vector<char> in_chart_;
};

}  // namespace OpenMeshSkinned
