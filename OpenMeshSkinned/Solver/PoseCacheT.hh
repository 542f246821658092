#pragma once
/** \file PoseCacheT.hh
 *  Per vertex and example pose: the posed position and the Garland-Heckbert quadric of the posed faces.
 *  Stored vertex-major (a vertex's poses side by side), as the solve reads them.
 *
 *  The stored positions are floats (12 bytes less per vertex and pose). Only the
 *  fold-over check reads them, where a rounding of 10^-7 of the model's size turns no face that matters;
 *  the quadrics are built from positions in doubles, and posed() computes one in doubles, or reads it
 *  when set_keep_exact() asked for them to be kept as well (the deviation bound reads them all the time).
 *
 *  Each quadric is stored about its vertex's stored posed position: about the origin, the surface far from
 *  it would be lost to cancellation. All ten numbers stay in doubles. With b and c in floats (64 bytes instead
 *  of 80), L&S's column rendered worse than gltfpack's LODs (bench/README.md, "Image-space judge"): on flat
 *  regions the geometry prices almost nothing, so the rounding decided which collapses came first there.
 *  quadric() gives a quadric back about the origin.
 */

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/NormalQuadric.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/ThreadFill.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class PoseCacheT {
public:
  using VertexHandle = typename Mesh::VertexHandle;

  explicit PoseCacheT(Mesh& mesh) : mesh_(mesh) {}

  /// Reads the example poses ("m:skin_poses"; std::invalid_argument when there are none) and fills both
  /// tables from the mesh as it is now, on up to \p threads threads (the tables do not depend on it).
  void build(int threads = 1) {
    h_inf_ = influences_handle(mesh_);
    poses_ = required_example_poses(mesh_);
    // Every solve downstream assumes finite poses: a NaN would never converge.
    for (const Pose& p : poses_)
      if (!p.finite())
        throw std::invalid_argument("example pose \"" + p.label + "\" has a non-finite transform or morph weight");
    P_ = static_cast<int>(poses_.size());
    const size_t nv = mesh_.n_vertices();
    threads = std::clamp(threads, 1, int(nv / 4096) + 1);
    // update() fills the doubles while exact_ holds any: kept only when asked for, after the quadrics.
    ThreadTable<LocalQuadric>().swap(quadric_);  // update() moves stored quadrics: none yet
    fill_on_threads(posed_, nv * P_, Eigen::Vector3f::Zero().eval(), threads);
    fill_on_threads(exact_, nv * P_, Eigen::Vector3d::Zero().eval(), threads);
    run_on_threads(threads, [&](int t) {  // each thread poses its own range of vertices
      for (size_t i = nv * t / threads; i < nv * (t + 1) / threads; ++i) {
        const VertexHandle vh(static_cast<int>(i));
        if (!mesh_.has_vertex_status() || !mesh_.status(vh).deleted()) update(vh);
      }
    });
    // Summed in doubles one pose at a time, then stored: a table of doubles for every pose would double the
    // peak.
    fill_on_threads(quadric_, nv * P_, LocalQuadric{}, threads);
    accumulate_quadrics_by_configuration(
        mesh_, P_, [this](VertexHandle v, int j) -> const Eigen::Vector3d& { return exact_[v.idx() * P_ + j]; },
        [](auto) { return 1.0; },
        [&](int j, const std::vector<PoseQuadric>& sum) {
          for (size_t i = 0; i < nv; ++i) set_quadric(VertexHandle(static_cast<int>(i)), j, sum[i]);
        },
        threads);
    if (!keep_exact_) ThreadTable<Eigen::Vector3d>().swap(exact_);
    normal_.clear();
    if (with_normals_) {
      // Scaled so that a normal off by one radian over a face weighs as much, per pose, as the face moved by
      // one mean edge length: the units of the geometric quadrics summed over the poses.
      // Summed face by face (the halfedges of each): the same to the last bit however the edges are numbered.
      double sum = 0.0;
      size_t n = 0;
      for (auto fh : mesh_.faces())
        for (auto h : mesh_.fh_range(fh)) {
          sum += mesh_.calc_edge_length(h);
          ++n;
        }
      const double s = n ? sum / n : 0.0;
      normal_quadrics(mesh_, s * s * P_, normal_, threads);
    }
  }
  /// Build the rest-pose normal quadrics too (NormalQuadric.hh), from the next build().
  void set_normal_quadrics(bool on) { with_normals_ = on; }
  /// Vertex \p v's normal quadric, or null when build() made none.
  const PoseQuadric* normal_quadric(VertexHandle v) const { return normal_.empty() ? nullptr : &normal_[v.idx()]; }
  /// Keep the posed positions in doubles too (from the next build()).
  void set_keep_exact(bool on) { keep_exact_ = on; }

  int n_poses() const { return P_; }
  const Pose& pose(int j) const { return poses_[j]; }
  const std::vector<Pose>& poses() const { return poses_; }
  OpenMesh::VPropHandleT<Influences> influences() const { return h_inf_; }

  /// Vertex \p v posed in pose \p j, in doubles (computed).
  Eigen::Vector3d posed(VertexHandle v, int j) const {
    if (!exact_.empty()) return exact_[v.idx() * P_ + j];
    return skin_point(to_eigen(mesh_.point(v)), mesh_.property(h_inf_, v), poses_[j]);
  }
  /// The same position as stored, in floats (the fold-over check's).
  Eigen::Vector3d posed_stored(int v, int j) const { return posed_[v * P_ + j].template cast<double>(); }
  /// Vertex \p v's quadric in pose \p j, about the origin.
  PoseQuadric quadric(VertexHandle v, int j) const {
    PoseQuadric q;
    add_quadric(v, j, q);
    return q;
  }
  /// Adds vertex \p v's quadric in pose \p j (about the origin) to \p into: the solve's summed endpoints,
  /// without a copy between.
  void add_quadric(VertexHandle v, int j, PoseQuadric& into) const {
    const size_t k = size_t(v.idx()) * P_ + j;
    const double px = posed_[k].x(), py = posed_[k].y(), pz = posed_[k].z();
    const LocalQuadric& l = quadric_[k];
    const double* A = l.A;
    const double apx = A[0] * px + A[1] * py + A[2] * pz;
    const double apy = A[1] * px + A[3] * py + A[4] * pz;
    const double apz = A[2] * px + A[4] * py + A[5] * pz;
    const double bx = l.b[0], by = l.b[1], bz = l.b[2];
    double* q = into.q;
    for (int i = 0; i < 6; ++i) q[kUpperA[i]] += A[i];
    // b = b' - A p, c = c' + p^T A p - 2 b'^T p, for b', c' about p.
    q[3] += bx - apx, q[6] += by - apy, q[8] += bz - apz;
    q[9] += l.c + (px * apx + py * apy + pz * apz) - 2.0 * (bx * px + by * py + bz * pz);
  }
  /// Stores \p q (about the origin) as vertex \p v's quadric in pose \p j.
  void set_quadric(VertexHandle v, int j, const PoseQuadric& q) {
    const size_t k = size_t(v.idx()) * P_ + j;
    const Eigen::Vector3d p = posed_[k].template cast<double>();
    const Eigen::Vector3d bl = q.A() * p + q.b();
    LocalQuadric& l = quadric_[k];
    for (int i = 0; i < 6; ++i) l.A[i] = q.q[kUpperA[i]];
    for (int i = 0; i < 3; ++i) l.b[i] = bl[i];
    l.c = q(p);
  }

  /// A rest position with a skin, posed in pose \p j.
  Eigen::Vector3d posed_point(const Eigen::Vector3d& rest, const Influences& w, int j) const {
    return skin_point(rest, w, poses_[j]);
  }

  /// Re-poses \p v after its rest position or skin changed.
  void update(VertexHandle v) {
    const Eigen::Vector3d rest = to_eigen(mesh_.point(v));
    const Influences& w = mesh_.property(h_inf_, v);
    for (int j = 0; j < P_; ++j) {
      const Eigen::Vector3d p = skin_point(rest, w, poses_[j]);
      // The quadric is stored about the old position: moved with it to the new one.
      const bool stored = !quadric_.empty();
      const PoseQuadric q = stored ? quadric(v, j) : PoseQuadric{};
      posed_[v.idx() * P_ + j] = p.template cast<float>();
      if (stored) set_quadric(v, j, q);
      if (!exact_.empty()) exact_[v.idx() * P_ + j] = p;
    }
  }

  /// \p into now stands for \p from's faces too.
  void merge_quadrics(VertexHandle from, VertexHandle into) {
    for (int j = 0; j < P_; ++j) {
      PoseQuadric q = quadric(into, j);
      add_quadric(from, j, q);
      set_quadric(into, j, q);
    }
    if (!normal_.empty()) normal_[into.idx()] += normal_[from.idx()];
  }

private:
  Mesh& mesh_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  std::vector<Pose> poses_;
  int P_ = 0;
  ThreadTable<Eigen::Vector3f> posed_;
  bool keep_exact_ = false;
  ThreadTable<Eigen::Vector3d> exact_;  // empty unless keep_exact_
  // Where LocalQuadric::A's entries sit in PoseQuadric.
  static constexpr int kUpperA[6] = {0, 1, 2, 4, 5, 7};
  struct LocalQuadric {
    // No initialisers: trivial, so that fill_on_threads() is the table's first write. LocalQuadric{} is zero.
    double A[6];     // the upper triangle of A
    double b[3], c;  // about the stored posed position
  };
  ThreadTable<LocalQuadric> quadric_;
  bool with_normals_ = false;
  std::vector<PoseQuadric> normal_;  // per vertex; empty unless with_normals_
};

}  // namespace OpenMeshSkinned
