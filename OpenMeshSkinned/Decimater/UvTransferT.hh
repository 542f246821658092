#pragma once
/** \file UvTransferT.hh
 *  Texture coordinates of a vertex that a collapse moved. After a collapse v1's corners hold stale UVs
 *  (v0's, or v1's at a position v1 has left): each corner is re-interpolated in the faces around the
 *  collapse as they were, restricted to the faces of the corner's UV chart, at the closest point of the
 *  closest such face. The chart is what keeps a seam a seam: a corner on one side of it must not take
 *  coordinates from the other side's island.
 *
 *  Usage, around each collapse: record() before, apply() after. Does nothing on a mesh without UVs (or
 *  with the attribute but all zero, as generated meshes carry it), so it costs nothing there.
 */

#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"

#include <cmath>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class UvTransferT {
public:
  using VertexHandle = typename Mesh::VertexHandle;

  explicit UvTransferT(Mesh& mesh) : mesh_(mesh) {}

  /// Looks for UVs to keep; call once before decimating (and again if the mesh gains UVs).
  void prepare() {
    active_ = false;
    if (!mesh_.has_halfedge_texcoords2D()) return;
    // Corners only: a border halfedge belongs to no face, and nothing sets (or reads) its UV, which may
    // hold anything; counting it made a UV-less 1M-triangle grid pay for UV bookkeeping (> 400 s).
    for (auto h : mesh_.halfedges())
      if (!mesh_.is_boundary(h) && (mesh_.texcoord2D(h)[0] != 0 || mesh_.texcoord2D(h)[1] != 0)) {
        active_ = true;
        return;
      }
  }
  bool active() const { return active_; }

  /// Remembers the faces around \p v0 and \p v1 with their corners' positions and UVs.
  void record(VertexHandle v0, VertexHandle v1) {
    sources_.clear();
    if (!active_) return;
    for (const VertexHandle c : {v0, v1})
      for (auto fh : mesh_.vf_range(c)) {
        Source s;
        int k = 0;
        for (auto h : mesh_.fh_range(fh)) {
          const auto t = mesh_.texcoord2D(h);
          s.p[k] = to_eigen(mesh_.point(mesh_.to_vertex_handle(h)));
          s.uv[k] = Eigen::Vector2d(t[0], t[1]);
          s.v[k] = mesh_.to_vertex_handle(h).idx();
          ++k;
        }
        sources_.push_back(s);
      }
  }

  /// Sets the UVs of \p v1's corners from the recorded faces at its current position. Call after the collapse.
  void apply(VertexHandle v1) {
    if (sources_.empty() || !mesh_.has_halfedge_texcoords2D()) return;
    const Eigen::Vector3d p = to_eigen(mesh_.point(v1));
    for (auto h : mesh_.vih_range(v1)) {
      if (mesh_.is_boundary(h)) continue;
      const auto hb = mesh_.next_halfedge_handle(h), hc = mesh_.next_halfedge_handle(hb);
      const auto tb = mesh_.texcoord2D(hb), tc = mesh_.texcoord2D(hc);
      mark_chart(mesh_.to_vertex_handle(hb).idx(), Eigen::Vector2d(tb[0], tb[1]), mesh_.to_vertex_handle(hc).idx(),
                 Eigen::Vector2d(tc[0], tc[1]));
      double best = HUGE_VAL;
      Eigen::Vector2d uv;
      for (size_t i = 0; i < sources_.size(); ++i) {
        if (!in_chart_[i]) continue;
        const Source& s = sources_[i];
        Eigen::Vector3d bary;
        const double d = closest_barycentric(s.p, p, bary);
        if (d < best) {
          best = d;
          uv = bary[0] * s.uv[0] + bary[1] * s.uv[1] + bary[2] * s.uv[2];
        }
      }
      if (best < HUGE_VAL) mesh_.set_texcoord2D(h, typename Mesh::TexCoord2D(uv.x(), uv.y()));
    }
  }

private:
  struct Source {
    Eigen::Vector3d p[3];
    Eigen::Vector2d uv[3];
    int v[3];
  };

  static bool same(const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return (x - y).norm() < kSeamUvTolerance; }

  // The chart of a corner whose other two vertices are b and c: the source faces that give b or c the
  // corner's UV, grown across edges whose two ends carry the same UVs on both sides (no seam).
  void mark_chart(int b, const Eigen::Vector2d& tb, int c, const Eigen::Vector2d& tc) {
    const size_t ns = sources_.size();
    in_chart_.assign(ns, 0);
    for (size_t i = 0; i < ns; ++i)
      for (int k = 0; k < 3; ++k) {
        const Source& s = sources_[i];
        if ((s.v[k] == b && same(s.uv[k], tb)) || (s.v[k] == c && same(s.uv[k], tc))) in_chart_[i] = 1;
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
              shared += sources_[i].v[a] == sources_[j].v[d] && same(sources_[i].uv[a], sources_[j].uv[d]);
          if (shared >= 2) in_chart_[i] = grew = 1;
        }
      }
    }
  }

  Mesh& mesh_;
  bool active_ = false;
  std::vector<Source> sources_;
  std::vector<char> in_chart_;
};

}  // namespace OpenMeshSkinned
