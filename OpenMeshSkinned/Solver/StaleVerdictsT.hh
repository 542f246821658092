#pragma once
/** \file StaleVerdictsT.hh
 *  Keeping DecimaterT's stored verdicts honest when collapses move vertices.
 *
 *  DecimaterT keeps, per vertex, only its cheapest legal collapse, priced once, with the binary modules
 *  asked then and never again. A placing priority module moves v1, which changes the faces of v1's old
 *  neighbours, yet DecimaterT re-prices only v0's old neighbours: the others keep verdicts made on the
 *  old geometry. This class
 *  - remembers, per vertex, the collapse DecimaterT stored for it (the cheapest legal one priced in the
 *    vertex's sweep), which also lets a binary module skip checks on collapses that cannot win;
 *  - after each collapse, re-checks the stored collapses near v1 and locks ("deferral") the vertices
 *    whose stored collapse would now fold, until DecimaterT re-prices them as someone's support (it skips
 *    a locked v0). Vertices the user locked are never touched; the marks live in a vertex property, so
 *    they survive garbage collection.
 *  The order of calls it relies on is listed in SolverModuleT.hh and pinned by test_decimater_contract.
 */

#include "OpenMeshSkinned/Collapse/CollapseLegality.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace OpenMeshSkinned {

/// Named vertex property marking the vertices the solver locked.
inline constexpr const char* kDeferredProperty = "v:omsk_deferred";

template <typename Mesh>
class StaleVerdictsT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  explicit StaleVerdictsT(Mesh& mesh) : mesh_(mesh) {}

  void prepare() {
    target_.assign(mesh_.n_vertices(), -1);
    seen_.assign(mesh_.n_vertices(), 0);
    pass_ = 0;
    sweep_v0_ = best_v0_ = -1;
    if (!mesh_.get_property_handle(deferred_, kDeferredProperty)) mesh_.add_property(deferred_, kDeferredProperty);
    for (auto vh : mesh_.all_vertices()) mesh_.property(deferred_, vh) = false;
  }

  /// The first call for a new v0 starts its sweep (DecimaterT re-prices all collapses of a vertex in a
  /// row) and forgets the collapse stored for it.
  void begin_pricing(const CollapseInfo& ci) {
    const int v0 = ci.v0.idx();
    if (sweep_v0_ == v0) return;
    sweep_v0_ = v0;
    best_v0_ = -1;
    if (static_cast<size_t>(v0) < target_.size()) target_[v0] = -1;
  }

  /// A collapse every binary module accepted, priced \p error: the vertex's stored one if the cheapest.
  void note_legal(const CollapseInfo& ci, double error) {
    const int v0 = ci.v0.idx();
    // Compared as DecimaterT compares priorities: in float, strictly smaller wins.
    if (best_v0_ != v0 || static_cast<float>(error) < static_cast<float>(best_error_)) {
      best_v0_ = v0;
      best_error_ = error;
      if (static_cast<size_t>(v0) < target_.size()) target_[v0] = ci.v0v1.idx();
    }
  }
  /// Whether a legal collapse from \p v0 was priced in its current sweep (costing best_error()).
  bool has_legal(VertexHandle v0) const { return best_v0_ == v0.idx(); }
  double best_error() const { return best_error_; }

  /// Before a collapse: the sweep ends, and v0's neighbours are the ones DecimaterT will re-price.
  void begin_collapse(const CollapseInfo& ci) {
    best_v0_ = sweep_v0_ = -1;
    ring_.clear();
    for (auto vh : mesh_.vv_range(ci.v0)) ring_.push_back(vh);
  }

  /** After a collapse into \p v1: unlocks the vertices DecimaterT is about to re-price, and locks those
   *  near v1 whose stored collapse \p folds (a predicate on a CollapseInfo) now. Returns how many it locked. */
  template <typename Folds>
  size_t defer_around(VertexHandle v1, Folds folds) {
    for (VertexHandle s : ring_)
      if (mesh_.property(deferred_, s)) {
        mesh_.status(s).set_locked(false);
        mesh_.property(deferred_, s) = false;
      }
    // A collapse z -> w is judged on the faces around z and around w, so z's stored collapse may be
    // stale when v1 is a neighbour of z, or of w.
    // Each vertex once per collapse: v1's neighbours first, then theirs (only when their collapse ends
    // next to v1). The neighbours are listed once instead of searched for each candidate.
    ++pass_;
    near_.clear();
    for (auto z : mesh_.vv_range(v1)) near_.push_back(z);
    size_t locked = 0;
    auto check = [&](VertexHandle z, bool must_end_next_to_v1) {
      if (seen_[z.idx()] == pass_) return;
      seen_[z.idx()] = pass_;
      if (z == v1 || mesh_.status(z).locked() || std::find(ring_.begin(), ring_.end(), z) != ring_.end()) return;
      const int t = target_[z.idx()];
      if (t < 0) return;
      const typename Mesh::HalfedgeHandle h(t);
      if (mesh_.status(mesh_.edge_handle(h)).deleted() || mesh_.from_vertex_handle(h) != z) return;
      if (must_end_next_to_v1 && std::find(near_.begin(), near_.end(), mesh_.to_vertex_handle(h)) == near_.end())
        return;
      if (folds(CollapseInfo(mesh_, h)) && link_condition_ok(mesh_, h)) {
        mesh_.status(z).set_locked(true);
        mesh_.property(deferred_, z) = true;
        ++locked;
      }
    };
    for (VertexHandle z : near_) check(z, false);
    for (VertexHandle z : near_)
      for (auto y : mesh_.vv_range(z)) check(y, true);
    return locked;
  }

  /// Unlocks every vertex this class locked.
  void release() {
    OpenMesh::VPropHandleT<bool> h;
    if (!mesh_.get_property_handle(h, kDeferredProperty)) return;
    for (auto vh : mesh_.all_vertices())
      if (mesh_.property(h, vh)) {
        mesh_.status(vh).set_locked(false);
        mesh_.property(h, vh) = false;
      }
  }

private:
  Mesh& mesh_;
  OpenMesh::VPropHandleT<bool> deferred_;
  std::vector<int> target_;  // per vertex: halfedge index of its stored collapse, -1 when none
  std::vector<VertexHandle> ring_, near_;
  std::vector<uint32_t> seen_;  // per vertex: the last defer_around pass that checked it
  uint32_t pass_ = 0;
  int sweep_v0_ = -1, best_v0_ = -1;
  double best_error_ = 0.0;
};

/// Unlocks the vertices the solver locked and removes its marks.
template <typename Mesh>
void release_stale_marks(Mesh& mesh) {
  OpenMesh::VPropHandleT<bool> d;
  if (!mesh.get_property_handle(d, kDeferredProperty)) return;
  StaleVerdictsT<Mesh>(mesh).release();
  mesh.remove_property(d);
}

}  // namespace OpenMeshSkinned
