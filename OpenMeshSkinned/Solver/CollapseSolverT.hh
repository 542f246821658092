#pragma once
/** \file CollapseSolverT.hh
 *  The one solve per candidate edge that all OpenMeshSkinned decimater modules share.
 *
 *  For an edge (v0, v1) it minimises the quartic error of Landreneau & Schaefer (eq. 3)
 *
 *      E(v, a) = sum_poses (sum_k a_k M_k v)^T (Q_v0 + Q_v1) (sum_k a_k M_k v)
 *
 *  over the rest position v and the weights a (support: the endpoints' joints) by alternating the 3x3
 *  vertex solve (3.1) and the constrained weight solve (3.2, WeightSolver), starting from the endpoints'
 *  average weights, until the error stops falling. The answer depends only on the two endpoints, so it
 *  is cached per edge and reused until either endpoint changes (vertex version stamps): DecimaterT asks
 *  for every edge around a collapse again, and most of those did not change.
 *
 *  The solver lives in the named mesh property "m:omsk_collapse_solver" (see shared_solver()), so the
 *  modules find each other's settings and work alone or in any combination.
 */

#include "OpenMeshSkinned/Decimater/MorphTransferT.hh"
#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/PoseQuadric.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"
#include "OpenMeshSkinned/Solver/WeightSolver.hh"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace OpenMeshSkinned {

/// The solver's answer for one edge.
struct CollapseResult {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< rest-pose position of the merged vertex
  Influences weights;                                 ///< its skin, within the cap
  double error = 0.0;                                 ///< quartic error E(position, weights), >= 0
  bool valid = false;                                 ///< false when the solve produced nothing finite
};

struct CollapseSolverStats {
  size_t requests = 0;     ///< times a module asked for an edge
  size_t solves = 0;       ///< edges actually solved
  size_t cache_hits = 0;   ///< answered from the cache
  size_t collapses = 0;
  size_t placement_fallbacks = 0;  ///< collapses whose solved position was stale and was replaced
  size_t forced_flips = 0;         ///< collapses DecimaterT made although every placement flips a face
  size_t deferred = 0;             ///< vertices held back until DecimaterT re-asked them (stale verdicts)
  WeightSolverStats weights;
};

/** A cost model other than the skinned quadric that places the merged vertex (e.g. the rest-pose
 *  quadric): set with CollapseSolverT::set_edge_model(); the solver then caches and applies its answers. */
template <typename Mesh>
class EdgeModelT {
public:
  virtual ~EdgeModelT() = default;
  virtual void solve_edge(typename Mesh::VertexHandle a, typename Mesh::VertexHandle b, CollapseResult& out) = 0;
};

template <typename Mesh>
class CollapseSolverT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using EdgeHandle = typename Mesh::EdgeHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  explicit CollapseSolverT(Mesh& mesh) : mesh_(mesh), morph_(mesh) {}

  // ---- settings (written by the modules' setters) ----------------------------------------------------

  /// Most influences a vertex may have (ModWeightCapT sets it; otherwise the storage capacity).
  void set_max_influences(int n) {
    max_influences_ = std::clamp(n, 1, Influences::kCapacity);
    invalidate_cache();
  }
  int max_influences() const { return max_influences_; }
  void set_cap_strategy(CapStrategy s) {
    strategy_ = s;
    invalidate_cache();
  }
  CapStrategy cap_strategy() const { return strategy_; }
  /// Whether the merged vertex takes the solved position and weights (ModSkinnedQuadricT turns it on).
  /// Off, a collapse is OpenMesh's plain halfedge collapse: v1 keeps its position and skin.
  void set_placement(bool on) { placement_ = on; }
  /// Replaces the skinned quadric as the source of placements and errors (nullptr restores it).
  void set_edge_model(EdgeModelT<Mesh>* model) {
    model_ = model;
    invalidate_cache();
  }
  bool placement() const { return placement_; }
  /// Largest normal rotation (radians) a collapse may cause in any pose; set by ModSkinnedFoldOverT.
  /// The placement is checked against it again at collapse time (see end_collapse()).
  void set_fold_over_angle(double rad) { fold_cos_ = std::cos(rad); fold_check_ = true; }
  bool fold_over_check() const { return fold_check_; }
  void set_max_iterations(int n) {
    max_iterations_ = std::max(1, n);
    invalidate_cache();
  }
  /// Forgets every cached edge answer (settings changed).
  void invalidate_cache() {
    for (auto& c : cache_) c.filled = false;
  }
  int max_iterations() const { return max_iterations_; }

  // ---- lifetime --------------------------------------------------------------------------------------

  /** Builds per-vertex, per-pose quadrics and posed positions from the mesh as it is now. Every module
   *  calls it from initialize(); only the first call of a decimation does the work. */
  void prepare() {
    if (prepared_) return;
    h_inf_ = influences_handle(mesh_);
    poses_ = example_poses(mesh_);
    if (poses_.empty()) poses_.push_back(Pose::identity(skeleton(mesh_).size()));
    P_ = static_cast<int>(poses_.size());
    const size_t nv = mesh_.n_vertices();
    posed_.assign(nv * P_, Eigen::Vector3d::Zero());
    quadric_.assign(nv * P_, PoseQuadric{});
    stamp_.assign(nv, 0);
    cache_.assign(mesh_.n_edges(), CacheEntry{});
    target_.assign(nv, -1);
    // UV bookkeeping only when there are UVs to keep (generated meshes carry the attribute, all zero).
    uv_active_ = false;
    if (mesh_.has_halfedge_texcoords2D())
      for (auto h : mesh_.halfedges())
        if (mesh_.texcoord2D(h)[0] != 0 || mesh_.texcoord2D(h)[1] != 0) {
          uv_active_ = true;
          break;
        }
    if (!mesh_.get_property_handle(deferred_, kDeferredProperty)) mesh_.add_property(deferred_, kDeferredProperty);
    for (auto vh : mesh_.all_vertices()) mesh_.property(deferred_, vh) = false;
    for (auto vh : mesh_.vertices()) update_posed(vh);
    accumulate_quadrics(
        mesh_, P_, [this](VertexHandle v, int j) { return posed(v, j); },
        [this](VertexHandle v, int j) -> PoseQuadric& { return quadric(v, j); });
    prepared_ = true;
  }

  bool prepared() const { return prepared_; }
  int n_poses() const { return P_; }
  const Pose& pose(int j) const { return poses_[j]; }
  const Eigen::Vector3d& posed(VertexHandle v, int j) const { return posed_[v.idx() * P_ + j]; }
  PoseQuadric& quadric(VertexHandle v, int j) { return quadric_[v.idx() * P_ + j]; }
  const PoseQuadric& quadric(VertexHandle v, int j) const { return quadric_[v.idx() * P_ + j]; }

  // ---- solving ---------------------------------------------------------------------------------------

  /// The optimal merged vertex for the edge of \p ci, from the cache when its endpoints did not change.
  const CollapseResult& solve(const CollapseInfo& ci) {
    ++stats_.requests;
    const EdgeHandle eh = mesh_.edge_handle(ci.v0v1);
    CacheEntry& ce = cache_[eh.idx()];
    const int a = std::min(ci.v0.idx(), ci.v1.idx()), b = std::max(ci.v0.idx(), ci.v1.idx());
    if (ce.filled && ce.va == a && ce.vb == b && ce.sa == stamp_[a] && ce.sb == stamp_[b]) {
      ++stats_.cache_hits;
      return ce.result;
    }
    ++stats_.solves;
    if (model_)
      model_->solve_edge(VertexHandle(a), VertexHandle(b), ce.result);
    else
      solve_edge(VertexHandle(a), VertexHandle(b), ce.result);
    ce.filled = true;
    ce.va = a;
    ce.vb = b;
    ce.sa = stamp_[a];
    ce.sb = stamp_[b];
    return ce.result;
  }

  /// The merged vertex's position in pose \p j for a given rest position and skin.
  Eigen::Vector3d posed_point(const Eigen::Vector3d& rest, const Influences& w, int j) const {
    return skin_point(rest, w, poses_[j]);
  }

  /** Whether collapsing \p ci, with the merged vertex at \p rest with skin \p w, turns any remaining face
   *  around it by more than the allowed angle, or makes it degenerate, in any pose. */
  bool flips(const CollapseInfo& ci, const Eigen::Vector3d& rest, const Influences& w, double min_cos) const {
    // The surviving faces around the collapse, as (center, a, b): the center becomes the merged vertex.
    // Gathered once, then checked pose by pose (circulating per pose costs more than the check).
    ring_faces_.clear();
    for (const VertexHandle center : {ci.v0, ci.v1}) {
      const VertexHandle other = center == ci.v0 ? ci.v1 : ci.v0;
      for (auto heh : mesh_.voh_range(center)) {
        if (mesh_.is_boundary(heh)) continue;
        const VertexHandle a = mesh_.to_vertex_handle(heh);
        const VertexHandle b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(heh));
        if (a != other && b != other) ring_faces_.push_back({center.idx(), a.idx(), b.idx()});
      }
    }
    for (int j = 0; j < P_; ++j) {
      const Eigen::Vector3d p = posed_point(rest, w, j);
      for (const auto& f : ring_faces_) {
        const Eigen::Vector3d &pc = posed_[f[0] * P_ + j], &pa = posed_[f[1] * P_ + j], &pb = posed_[f[2] * P_ + j];
        const Eigen::Vector3d n_old = (pa - pc).cross(pb - pc);
        const Eigen::Vector3d n_new = (pa - p).cross(pb - p);
        const double l2_new = n_new.squaredNorm(), l2_old = n_old.squaredNorm();
        const double scale = std::max({(pa - p).squaredNorm(), (pb - p).squaredNorm(), (pa - pb).squaredNorm()});
        if (l2_new <= 1e-20 * scale * scale) return true;  // degenerate
        if (l2_old <= 0.0) continue;
        const double d = n_new.dot(n_old);
        // d < min_cos |n_new||n_old|, without square roots.
        if (min_cos >= 0.0 ? (d < 0.0 || d * d < min_cos * min_cos * l2_new * l2_old)
                           : (d < 0.0 && d * d > min_cos * min_cos * l2_new * l2_old))
          return true;
      }
    }
    return false;
  }

  // ---- pruning the binary checks ---------------------------------------------------------------------
  // A decimater keeps, for each vertex, only its cheapest legal collapse. Once the priority module has
  // priced a legal collapse from v0 at e, any other collapse from v0 costing at least e cannot be chosen,
  // so its expensive binary checks (fold-over in every pose) can be skipped. The record is per v0 and is
  // forgotten at every collapse.

  /// Called by the priority module for a collapse that every binary module accepted. Also remembers,
  /// per vertex, its cheapest legal collapse: the one DecimaterT stores as the vertex's target.
  void note_legal_priority(const CollapseInfo& ci, double error) {
    const int v0 = ci.v0.idx();
    // Compared as DecimaterT compares priorities: in float, strictly smaller wins.
    if (best_v0_ != v0 || static_cast<float>(error) < static_cast<float>(best_error_)) {
      best_v0_ = v0;
      best_error_ = error;
      if (static_cast<size_t>(v0) < target_.size()) target_[v0] = ci.v0v1.idx();
    }
  }
  /// Every module calls this first in collapse_priority: the first call for a new v0 starts its sweep
  /// (DecimaterT re-prices all collapses of a vertex in a row) and forgets its stored collapse.
  void begin_pricing(const CollapseInfo& ci) {
    const int v0 = ci.v0.idx();
    if (sweep_v0_ == v0) return;
    sweep_v0_ = v0;
    best_v0_ = -1;
    if (static_cast<size_t>(v0) < target_.size()) target_[v0] = -1;
  }

  /// Whether \p ci cannot win over a legal collapse already priced for the same v0.
  bool cannot_win(const CollapseInfo& ci) {
    if (!placement_ || best_v0_ != ci.v0.idx()) return false;
    return solve(ci).error >= best_error_;
  }

  /// Where and with which skin the merged vertex will be if \p ci is collapsed now.
  void placement_of(const CollapseInfo& ci, Eigen::Vector3d& rest, Influences& w) {
    if (placement_) {
      const CollapseResult& r = solve(ci);
      if (r.valid) {
        rest = r.position;
        w = r.weights;
        return;
      }
    }
    rest = to_eigen(mesh_.point(ci.v1));
    w = mesh_.property(h_inf_, ci.v1);
  }

  // ---- collapse bookkeeping (every module forwards its pre/postprocess; the first call does the work) --

  void begin_collapse(const CollapseInfo& ci) {
    if (pending_) return;
    pending_ = true;
    best_v0_ = -1;
    sweep_v0_ = -1;
    pending_result_.valid = false;
    ring_.clear();
    for (auto vh : mesh_.vv_range(ci.v0)) ring_.push_back(vh);  // what DecimaterT re-asks afterwards
    record_uv_sources(ci);
    morph_.record(ci.v0, ci.v1);
    if (!placement_) return;
    pending_result_ = solve(ci);
    if (!fold_check_ || !pending_result_.valid || !flips(ci, pending_result_.position, pending_result_.weights, fold_cos_))
      return;
    // DecimaterT does not re-ask binary modules when it pops a collapse, and it re-asks only the vertices
    // around v0 after each collapse, not those around a moved v1: the verdict may be stale. Place the
    // vertex where it flips nothing now, trying the solved weights at the endpoints and the midpoint,
    // then v1 as it is.
    ++stats_.placement_fallbacks;
    const Eigen::Vector3d p0 = to_eigen(mesh_.point(ci.v0)), p1 = to_eigen(mesh_.point(ci.v1));
    const Influences solved = pending_result_.weights;
    const Influences& w0 = mesh_.property(h_inf_, ci.v0);
    const Influences& w1 = mesh_.property(h_inf_, ci.v1);
    const std::pair<Eigen::Vector3d, const Influences*> candidates[] = {
        {p1, &solved}, {Eigen::Vector3d(0.5 * (p0 + p1)), &solved}, {p0, &solved}, {p1, &w1}, {p0, &w0}};
    for (const auto& [p, w] : candidates) {
      if (w->size() <= max_influences_ && !flips(ci, p, *w, fold_cos_)) {
        pending_result_.position = p;
        pending_result_.weights = *w;
        return;
      }
    }
    pending_result_.valid = false;
    ++stats_.forced_flips;
  }

  void end_collapse(const CollapseInfo& ci) {
    if (!pending_) return;
    pending_ = false;
    ++stats_.collapses;
    const VertexHandle v0 = ci.v0, v1 = ci.v1;
    for (int j = 0; j < P_; ++j) quadric(v1, j) += quadric(v0, j);
    if (placement_ && pending_result_.valid) {
      const Eigen::Vector3d& p = pending_result_.position;
      mesh_.set_point(v1, typename Mesh::Point(p.x(), p.y(), p.z()));
      mesh_.property(h_inf_, v1) = pending_result_.weights;
      update_posed(v1);
      if (mesh_.has_face_normals())
        for (auto fh : mesh_.vf_range(v1)) mesh_.set_normal(fh, mesh_.calc_face_normal(fh));
    } else if (mesh_.property(h_inf_, v1).size() > max_influences_) {
      reduce_vertex(v1);
    }
    // Moved or not, v1's corners that came from v0 carry v0's UVs: re-interpolate all of them.
    reassign_uvs(v1, to_eigen(mesh_.point(v1)));
    morph_.apply(v1);
    ++stamp_[v1.idx()];
    ++stamp_[v0.idx()];
    // Moved or not, v1 now holds v0's faces: verdicts around it may be stale. (After the stamps: the
    // re-checks must not reuse answers cached for v1 as it was.)
    if (placement_ && fold_check_) defer_stale_neighbours(v1);
  }

  /// Unlocks every vertex the solver deferred (see defer_stale_neighbours()); modules call it when done.
  void release_deferred() {
    OpenMesh::VPropHandleT<bool> h;
    if (!mesh_.get_property_handle(h, kDeferredProperty)) return;
    for (auto vh : mesh_.all_vertices())
      if (mesh_.property(h, vh)) {
        mesh_.status(vh).set_locked(false);
        mesh_.property(h, vh) = false;
      }
  }

  /// Named vertex property marking the vertices the solver locked (it survives garbage collection).
  static constexpr const char* kDeferredProperty = "v:omsk_deferred";

  /** Reduces every vertex with more than max_influences() bones by the weight solve on its own quadrics
   *  at its own position (not by plain truncation). Returns how many vertices changed. */
  size_t reduce_input_influences() {
    size_t changed = 0;
    for (auto vh : mesh_.vertices())
      if (mesh_.property(h_inf_, vh).size() > max_influences_) {
        reduce_vertex(vh);
        ++changed;
      }
    return changed;
  }

  const CollapseSolverStats& stats() const {
    stats_.weights = weights_.stats();
    return stats_;
  }
  WeightSolver& weight_solver() { return weights_; }

private:
  struct CacheEntry {
    CollapseResult result;
    int va = -1, vb = -1;
    uint32_t sa = 0, sb = 0;
    bool filled = false;
  };
  using Stats = CollapseSolverStats;

  // Moving v1 changes faces of v1's old neighbours, but DecimaterT re-asks only v0's old neighbours: the
  // others keep collapse verdicts made on the old geometry, and the fold-over check behind them is then
  // stale. Lock them (DecimaterT skips a locked v0) until DecimaterT re-asks them as someone's support;
  // never touch a vertex the user locked.
  void defer_stale_neighbours(VertexHandle v1) {
    for (VertexHandle s : ring_)
      if (mesh_.property(deferred_, s)) {
        mesh_.status(s).set_locked(false);
        mesh_.property(deferred_, s) = false;
      }
    // A collapse z -> w is judged on the faces around z and around w, so z's stored collapse may be
    // stale when v1 is a neighbour of z, or of w. Lock z when that collapse (the cheapest legal one the
    // priority module priced for z) would now flip a face.
    Eigen::Vector3d rest;
    Influences w;
    auto check = [&](VertexHandle z, bool must_end_next_to_v1) {
      if (z == v1 || mesh_.status(z).locked() || std::find(ring_.begin(), ring_.end(), z) != ring_.end()) return;
      const int t = target_[z.idx()];
      if (t < 0) return;
      const typename Mesh::HalfedgeHandle h(t);
      if (mesh_.status(mesh_.edge_handle(h)).deleted() || mesh_.from_vertex_handle(h) != z) return;
      if (must_end_next_to_v1 && mesh_.find_halfedge(mesh_.to_vertex_handle(h), v1) == typename Mesh::HalfedgeHandle())
        return;
      const CollapseInfo zc(mesh_, h);
      placement_of(zc, rest, w);
      if (flips(zc, rest, w, fold_cos_) && mesh_.is_collapse_ok(h)) {
        mesh_.status(z).set_locked(true);
        mesh_.property(deferred_, z) = true;
        ++stats_.deferred;
      }
    };
    for (auto z : mesh_.vv_range(v1)) {
      check(z, false);
      for (auto y : mesh_.vv_range(z)) check(y, true);
    }
  }

  // ---- texture coordinates of a moved vertex ----------------------------------------------------------
  // After a collapse v1's corners hold stale UVs (v0's, or v1's at a position v1 has left): each corner
  // is re-interpolated in the faces around the collapse as they were, restricted to faces of the same UV chart (those that give one of the corner's
  // two other vertices the same UV), at the closest point of the closest such face.
  struct UvSource {
    Eigen::Vector3d p[3];
    Eigen::Vector2d uv[3];
    int v[3];
  };

  void record_uv_sources(const CollapseInfo& ci) {
    uv_sources_.clear();
    if (!uv_active_) return;
    for (const VertexHandle c : {ci.v0, ci.v1})
      for (auto fh : mesh_.vf_range(c)) {
        UvSource s;
        int k = 0;
        for (auto h : mesh_.fh_range(fh)) {
          const auto t = mesh_.texcoord2D(h);
          s.p[k] = to_eigen(mesh_.point(mesh_.to_vertex_handle(h)));
          s.uv[k] = Eigen::Vector2d(t[0], t[1]);
          s.v[k] = mesh_.to_vertex_handle(h).idx();
          ++k;
        }
        uv_sources_.push_back(s);
      }
  }

  void reassign_uvs(VertexHandle v1, const Eigen::Vector3d& p) {
    if (uv_sources_.empty() || !mesh_.has_halfedge_texcoords2D()) return;
    for (auto h : mesh_.vih_range(v1)) {
      if (mesh_.is_boundary(h)) continue;
      const auto hb = mesh_.next_halfedge_handle(h), hc = mesh_.next_halfedge_handle(hb);
      const VertexHandle b = mesh_.to_vertex_handle(hb), c = mesh_.to_vertex_handle(hc);
      const auto tb = mesh_.texcoord2D(hb), tc = mesh_.texcoord2D(hc);
      // The chart: source faces that give b or c the corner's UV, grown across edges whose two ends
      // carry the same UVs on both sides (no seam).
      const size_t ns = uv_sources_.size();
      in_chart_.assign(ns, 0);
      auto same = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return (x - y).norm() < 1e-6; };
      for (size_t i = 0; i < ns; ++i)
        for (int k = 0; k < 3; ++k) {
          const UvSource& s = uv_sources_[i];
          if ((s.v[k] == b.idx() && same(s.uv[k], Eigen::Vector2d(tb[0], tb[1]))) ||
              (s.v[k] == c.idx() && same(s.uv[k], Eigen::Vector2d(tc[0], tc[1]))))
            in_chart_[i] = 1;
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
                shared += uv_sources_[i].v[a] == uv_sources_[j].v[d] && same(uv_sources_[i].uv[a], uv_sources_[j].uv[d]);
            if (shared >= 2) in_chart_[i] = grew = 1;
          }
        }
      }
      double best = HUGE_VAL;
      Eigen::Vector2d uv;
      for (size_t i = 0; i < ns; ++i) {
        if (!in_chart_[i]) continue;
        const UvSource& s = uv_sources_[i];
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

  void update_posed(VertexHandle v) {
    const Eigen::Vector3d rest = to_eigen(mesh_.point(v));
    const Influences& w = mesh_.property(h_inf_, v);
    for (int j = 0; j < P_; ++j) posed_[v.idx() * P_ + j] = skin_point(rest, w, poses_[j]);
  }

  // E(v, a) for the summed quadrics of the current edge.
  double energy(const Eigen::Vector3d& v, const WeightSolver::Vector& a) const {
    double e = 0.0;
    for (int j = 0; j < P_; ++j) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int k = 0; k < m_; ++k) p += a[k] * (M_[j * kMaxSupport + k] * v.homogeneous());
      e += Q_[j](p);
    }
    return std::max(e, 0.0);
  }

  // Sum_j B_j^T A_j B_j v = -Sum_j B_j^T (A_j t_j + b_j), B_j, t_j the blended matrix of pose j.
  // Directions the quadrics barely constrain (along a straight crease, across a flat patch) are left at
  // the reference point \p ref (Lindstrom's truncated pseudo-inverse): solving them exactly would fling
  // the vertex far along a valley of near-zero error. Returns false when nothing is constrained.
  bool vertex_step(const WeightSolver::Vector& a, const Eigen::Vector3d& ref, Eigen::Vector3d& v,
                   bool& full_rank) const {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int j = 0; j < P_; ++j) {
      Affine3 B = Affine3::Zero();
      for (int k = 0; k < m_; ++k) B += a[k] * M_[j * kMaxSupport + k];
      const Eigen::Matrix3d R = B.leftCols<3>();
      const Eigen::Vector3d t = B.col(3);
      const Eigen::Matrix3d Aj = Q_[j].A();
      A += R.transpose() * Aj * R;
      rhs -= R.transpose() * (Aj * t + Q_[j].b());
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(A);  // closed form for 3x3, several times faster than the iterative solver
    const Eigen::Vector3d ev = es.eigenvalues();
    if (!(ev[2] > 0.0)) return false;
    const Eigen::Vector3d r = es.eigenvectors().transpose() * (rhs - A * ref);
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    full_rank = true;
    for (int i = 0; i < 3; ++i) {
      if (ev[i] > kPseudoInverseCutoff * ev[2])
        d[i] = r[i] / ev[i];
      else
        full_rank = false;
    }
    v = ref + es.eigenvectors() * d;
    return v.allFinite();
  }

  // H = Sum_j V_j^T Q_j V_j with V_j's columns [M_k v; 1].
  void weight_matrix(const Eigen::Vector3d& v, WeightSolver::Matrix& H) const {
    H.setZero(m_, m_);
    Eigen::Matrix<double, 4, Eigen::Dynamic, 0, 4, WeightSolver::kMaxJoints> V(4, m_);
    for (int j = 0; j < P_; ++j) {
      for (int k = 0; k < m_; ++k) {
        V.col(k).head<3>() = M_[j * kMaxSupport + k] * v.homogeneous();
        V(3, k) = 1.0;
      }
      const Eigen::Matrix4d Q = Q_[j].matrix();
      H.noalias() += V.transpose() * Q * V;
    }
  }

  void solve_edge(VertexHandle va, VertexHandle vb, CollapseResult& out) {
    const Influences& wa = mesh_.property(h_inf_, va);
    const Influences& wb = mesh_.property(h_inf_, vb);
    m_ = 0;
    for (const JointWeight& jw : wa) joints_[m_++] = jw.joint;
    for (const JointWeight& jw : wb)
      if (std::find(joints_.begin(), joints_.begin() + m_, jw.joint) == joints_.begin() + m_) joints_[m_++] = jw.joint;
    Q_.resize(P_);
    M_.resize(static_cast<size_t>(P_) * kMaxSupport);
    for (int j = 0; j < P_; ++j) {
      Q_[j] = quadric(va, j);
      Q_[j] += quadric(vb, j);
      for (int k = 0; k < m_; ++k) M_[j * kMaxSupport + k] = poses_[j].joint[joints_[k]];
    }
    WeightSolver::Vector start(m_), a(m_);
    for (int k = 0; k < m_; ++k) start[k] = 0.5 * (wa.weight_of(joints_[k]) + wb.weight_of(joints_[k]));
    const Eigen::Vector3d pa = to_eigen(mesh_.point(va)), pb = to_eigen(mesh_.point(vb));

    a = start;
    Eigen::Vector3d v;
    double e = alternate(pa, pb, start, a, v, m_ > 1 ? Influences::kCapacity : 1);
    if (count_nonzero(a) > max_influences_) {
      // Cap after the free optimum (paper 3.2), then optimise again on the kept joints only.
      WeightSolver::Matrix H;
      weight_matrix(v, H);
      weights_.solve_capped(H, start, max_influences_, strategy_, a);
      e = alternate_fixed_support(pa, pb, start, a, v);
    }
    out.valid = v.allFinite() && std::isfinite(e);
    out.position = v;
    out.error = e;
    out.weights.clear();
    for (int k = 0; k < m_; ++k)
      if (a[k] > 0.0) out.weights.push(joints_[k], a[k]);
    out.weights.normalize();
    out.weights.sort();
  }

  static int count_nonzero(const WeightSolver::Vector& a) { return static_cast<int>((a.array() > 0.0).count()); }

  // The vertex step, then the best of it, the endpoints and the midpoint: the truncated solve is the
  // optimum only along the constrained directions, and a fully singular system has no solve at all.
  Eigen::Vector3d place(const Eigen::Vector3d& pa, const Eigen::Vector3d& pb, const WeightSolver::Vector& a) const {
    const Eigen::Vector3d mid = 0.5 * (pa + pb);
    Eigen::Vector3d cand[4] = {mid, pa, pb, mid};
    bool full_rank = false;
    int n = vertex_step(a, mid, cand[3], full_rank) ? 4 : 3;
    // A thin part (a tail, a finger) has quadrics whose minimum lies far along its axis: the error keeps
    // falling a little as the vertex slides out of the mesh. Optima more than an edge length beyond the
    // edge's midpoint are such valleys, not features: keep to the endpoints and the midpoint there.
    if (n == 4 && (cand[3] - mid).squaredNorm() > kMaxReach * kMaxReach * (pa - pb).squaredNorm()) n = 3;
    if (n == 4 && full_rank) return cand[3];  // the exact minimiser: nothing can beat it
    int best = 0;
    double be = energy(cand[0], a);
    for (int i = 1; i < n; ++i) {
      const double ei = energy(cand[i], a);
      if (ei < be) {
        be = ei;
        best = i;
      }
    }
    return cand[best];
  }

  // Alternating minimisation (paper 3.1/3.2); each half-step cannot increase E, so stop when it stalls.
  double alternate(const Eigen::Vector3d& pa, const Eigen::Vector3d& pb, const WeightSolver::Vector& start,
                   WeightSolver::Vector& a, Eigen::Vector3d& v, int cap) {
    WeightSolver::Matrix H;
    double e_prev = std::numeric_limits<double>::infinity();
    double e = e_prev;
    for (int it = 0; it < max_iterations_; ++it) {
      v = place(pa, pb, a);
      if (m_ == 1) return energy(v, a);
      weight_matrix(v, H);
      e = cap < m_ ? weights_.solve_capped(H, start, cap, strategy_, a) : weights_.solve(H, start, a);
      if (!(e < e_prev * (1.0 - 1e-4))) break;
      e_prev = e;
    }
    return energy(v, a);
  }

  // As alternate(), with the weights restricted to their current support.
  double alternate_fixed_support(const Eigen::Vector3d& pa, const Eigen::Vector3d& pb,
                                 const WeightSolver::Vector& start, WeightSolver::Vector& a, Eigen::Vector3d& v) {
    Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, WeightSolver::kMaxJoints, 1> active(m_);
    for (int k = 0; k < m_; ++k) active[k] = a[k] > 0.0;
    WeightSolver::Matrix H;
    double e_prev = std::numeric_limits<double>::infinity();
    for (int it = 0; it < max_iterations_; ++it) {
      v = place(pa, pb, a);
      weight_matrix(v, H);
      const double e = weights_.solve(H, start, a, &active);
      if (!(e < e_prev * (1.0 - 1e-4))) break;
      e_prev = e;
    }
    return energy(v, a);
  }

  // A vertex with too many bones: weight solve on its own quadrics at its own position, capped.
  void reduce_vertex(VertexHandle vh) {
    const Influences& w = mesh_.property(h_inf_, vh);
    m_ = 0;
    for (const JointWeight& jw : w) joints_[m_++] = jw.joint;
    Q_.resize(P_);
    M_.resize(static_cast<size_t>(P_) * kMaxSupport);
    for (int j = 0; j < P_; ++j) {
      Q_[j] = quadric(vh, j);
      for (int k = 0; k < m_; ++k) M_[j * kMaxSupport + k] = poses_[j].joint[joints_[k]];
    }
    WeightSolver::Vector start(m_), a(m_);
    for (int k = 0; k < m_; ++k) start[k] = w[k].weight;
    WeightSolver::Matrix H;
    weight_matrix(to_eigen(mesh_.point(vh)), H);
    weights_.solve_capped(H, start, max_influences_, strategy_, a);
    Influences out;
    for (int k = 0; k < m_; ++k)
      if (a[k] > 0.0) out.push(joints_[k], a[k]);
    out.normalize();
    out.sort();
    mesh_.property(h_inf_, vh) = out;
    update_posed(vh);
    ++stamp_[vh.idx()];
  }

  static constexpr int kMaxSupport = 2 * Influences::kCapacity;
  // Eigenvalues below this fraction of the largest count as unconstrained directions.
  static constexpr double kPseudoInverseCutoff = 1e-3;
  // How far (in edge lengths) from the edge's midpoint a solved position may lie.
  static constexpr double kMaxReach = 1.0;

  Mesh& mesh_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  std::vector<Pose> poses_;
  int P_ = 0;
  std::vector<Eigen::Vector3d> posed_;
  std::vector<PoseQuadric> quadric_;
  std::vector<uint32_t> stamp_;
  std::vector<CacheEntry> cache_;
  bool prepared_ = false;

  int max_influences_ = Influences::kCapacity;
  // TopN measured better on real characters (bench/README.md, cap-strategy workload).
  CapStrategy strategy_ = CapStrategy::TopN;
  bool placement_ = false;
  EdgeModelT<Mesh>* model_ = nullptr;
  bool fold_check_ = false;
  double fold_cos_ = 0.0;
  int max_iterations_ = 8;

  bool pending_ = false;
  int best_v0_ = -1;
  int sweep_v0_ = -1;
  std::vector<int> target_;  // per vertex: halfedge index of its cheapest legal collapse, -1 when none
  double best_error_ = 0.0;
  std::vector<VertexHandle> ring_;
  std::vector<UvSource> uv_sources_;
  MorphTransferT<Mesh> morph_;
  std::vector<char> in_chart_;
  bool uv_active_ = false;
  mutable std::vector<std::array<int, 3>> ring_faces_;
  OpenMesh::VPropHandleT<bool> deferred_;
  CollapseResult pending_result_;

  // Scratch for the edge being solved (kept to avoid allocating per solve).
  int m_ = 0;
  std::array<int, kMaxSupport> joints_{};
  std::vector<PoseQuadric> Q_;
  std::vector<Affine3> M_;
  WeightSolver weights_;
  mutable Stats stats_;
};

/// Name of the mesh property holding the shared solver.
inline constexpr const char* kSolverProperty = "m:omsk_collapse_solver";

/** The solver shared by all modules on \p mesh, created on first use. \p created tells the caller it
 *  made the property (and so must remove it when done). */
template <typename Mesh>
std::shared_ptr<CollapseSolverT<Mesh>> shared_solver(Mesh& mesh, bool& created) {
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> h;
  created = false;
  if (!mesh.get_property_handle(h, kSolverProperty)) {
    mesh.add_property(h, kSolverProperty);
    created = true;
  }
  auto& sp = mesh.property(h);
  if (!sp) sp = std::make_shared<CollapseSolverT<Mesh>>(mesh);
  return sp;
}

/// Removes the solver property (called by the module that created it).
template <typename Mesh>
void release_shared_solver(Mesh& mesh) {
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> h;
  if (mesh.get_property_handle(h, kSolverProperty)) mesh.remove_property(h);
  OpenMesh::VPropHandleT<bool> d;
  if (mesh.get_property_handle(d, CollapseSolverT<Mesh>::kDeferredProperty)) mesh.remove_property(d);
}

}  // namespace OpenMeshSkinned
