#pragma once
/** \file LazyDecimaterT.hh */

#include "OpenMeshSkinned/Collapse/CollapseLegality.hh"
#include "OpenMeshSkinned/Collapse/DriverHints.hh"

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>

#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <queue>
#include <thread>
#include <vector>

namespace OpenMeshSkinned {

struct LazyDecimaterStats {
  size_t priced = 0;    ///< priority module calls
  size_t stale = 0;     ///< popped candidates whose neighbourhood had changed, re-priced and pushed back
  size_t refused = 0;   ///< popped candidates a binary module or the topology refused
  size_t requeued = 0;  ///< accepted candidates queued again: the binary modules' verdict raised their price
  size_t collapses = 0;
};

/** A decimater with DecimaterT's interface that drives any OpenMesh ModBaseT modules, re-pricing lazily.
 *
 *  DecimaterT keeps one candidate per vertex and, after every collapse, re-prices every collapse of the
 *  removed vertex's neighbours (binary modules included), about 36 pricings; it never re-asks the
 *  binary modules when it pops, so a verdict made before a neighbour moved can be stale. This driver
 *  keeps a heap of halfedge candidates priced by the priority module alone, each with a version stamp of
 *  its endpoints' neighbourhoods:
 *  - after a collapse it only bumps the stamps of the surviving vertex and its ring (the vertices whose
 *    faces changed; v1 alone when the priority module is an EndpointPriority) and re-queues their
 *    candidates that had left the heap;
 *  - a popped candidate whose stamp is out of date is re-priced and pushed back; with priorities that
 *    only grow as quadrics accumulate (ModQuadricT, the skinned quadric) its old key is a lower bound,
 *    so nothing is taken out of order;
 *  - binary modules are asked when a candidate is popped with an up-to-date stamp, right before the
 *    collapse: verdicts are never stale (modules learn this from checks_at_pop(), DriverHints.hh).
 *  Modules implementing BatchPricing compute their answers for all edges first on set_threads() threads
 *  (and may keep a thread working during the run: the shared solver solves ahead, SolveAhead.hh).
 *  When the priority module prices both directions of an edge alike (EdgePriority), the heap holds edges,
 *  and a popped edge collapses in the first legal direction.
 *
 *  Modules must be added through this class (it keeps its own list to tell binary modules from the
 *  priority one, by DecimaterT's rule).
 *
 *  \code
 *  OpenMeshSkinned::LazyDecimaterT<Mesh> dec(mesh);
 *  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
 *  dec.add(hq);
 *  dec.initialize();
 *  dec.decimate_to_faces(0, 1000);
 *  \endcode
 */
template <typename MeshT>
class LazyDecimaterT : public OpenMesh::Decimater::BaseDecimaterT<MeshT> {
  using Base = OpenMesh::Decimater::BaseDecimaterT<MeshT>;

public:
  using Mesh = MeshT;
  using Module = typename Base::Module;
  using CollapseInfo = typename Base::CollapseInfo;
  using HalfedgeHandle = typename Mesh::HalfedgeHandle;
  using VertexHandle = typename Mesh::VertexHandle;

  explicit LazyDecimaterT(Mesh& mesh) : Base(mesh), mesh_(mesh) {}
  ~LazyDecimaterT() override { set_checks_at_pop(mesh_, false); }

  template <typename M>
  bool add(OpenMesh::Decimater::ModHandleT<M>& h) {
    if (!Base::add(h)) return false;
    modules_.push_back(&Base::module(h));
    priority_ = nullptr;
    return true;
  }
  template <typename M>
  bool remove(OpenMesh::Decimater::ModHandleT<M>& h) {
    Module* m = h.is_valid() ? &Base::module(h) : nullptr;
    if (!Base::remove(h)) return false;
    modules_.erase(std::remove(modules_.begin(), modules_.end(), m), modules_.end());
    priority_ = nullptr;
    return true;
  }

  /// As DecimaterT's: false unless exactly one priority module (or one named "Quadric") was added.
  bool initialize() {
    set_checks_at_pop(mesh_, true);  // before the modules' initialize(): they may read it there
    if (!Base::initialize()) return false;
    priority_ = nullptr;
    binary_.clear();
    for (Module* m : modules_)
      if (!m->is_binary()) priority_ = m;
    if (!priority_)
      for (Module* m : modules_)
        if (m->name() == "Quadric") priority_ = m;
    for (Module* m : modules_)
      if (m != priority_) binary_.push_back(m);
    const auto* ep = priority_ ? dynamic_cast<EndpointPriority*>(priority_) : nullptr;
    endpoint_priority_ = ep && ep->prices_by_endpoints();
    const auto* edge = priority_ ? dynamic_cast<EdgePriority*>(priority_) : nullptr;
    by_edge_ = edge && edge->prices_edges();
    return priority_ != nullptr;
  }

  /// Threads for modules that price all edges ahead (BatchPricing); default: the hardware's.
  void set_threads(int n) { threads_ = std::max(1, n); }
  int threads() const { return threads_; }

  /** Whether the mesh's topology still allows a collapse (DecimaterT's is_collapse_legal, which the modules
   *  are not asked about): when it does not, the mesh is as small as its pieces can get by collapses. */
  bool topology_allows_a_collapse() {
    for (auto h : mesh_.halfedges())
      if (!mesh_.status(mesh_.edge_handle(h)).deleted() && collapse_legal(mesh_, CollapseInfo(mesh_, h))) return true;
    return false;
  }

  /// \p n collapses at most (0: as many as possible). Returns the number made.
  size_t decimate(size_t n = 0, bool only_selected = false) {
    if (!n) n = mesh_.n_vertices();
    return run(only_selected, [&](size_t done, size_t, size_t) { return done < n; });
  }
  /// Collapses until at most \p n vertices remain (counting deleted ones as DecimaterT does).
  size_t decimate_to(size_t n, bool only_selected = false) {
    return n < mesh_.n_vertices() ? decimate(mesh_.n_vertices() - n, only_selected) : 0;
  }
  /// Collapses until \p nv vertices or \p nf faces remain (0: no limit), counted as DecimaterT counts.
  size_t decimate_to_faces(size_t nv = 0, size_t nf = 0, bool only_selected = false) {
    if (nv >= mesh_.n_vertices() || nf >= mesh_.n_faces()) return 0;
    return run(only_selected, [&](size_t, size_t v, size_t f) { return nv < v && nf < f; });
  }

  const LazyDecimaterStats& stats() const { return stats_; }

private:
  // A candidate is a halfedge, or an edge when the priority module prices both directions alike
  // (EdgePriority): then both halfedges are tried when it is popped.
  struct Candidate {
    float key;
    int slot;
    uint32_t stamp;
    // A min-heap on (key, slot index): ties resolve the same way on every run.
    bool operator<(const Candidate& o) const { return key != o.key ? key > o.key : slot > o.slot; }
  };

  HalfedgeHandle halfedge_of(int slot, int dir = 0) const {
    return by_edge_ ? mesh_.halfedge_handle(typename Mesh::EdgeHandle(slot), dir) : HalfedgeHandle(slot);
  }
  int slot_of(HalfedgeHandle h) const { return by_edge_ ? mesh_.edge_handle(h).idx() : h.idx(); }
  uint32_t stamp_of(HalfedgeHandle h) const {
    return std::max(stamp_[mesh_.from_vertex_handle(h).idx()], stamp_[mesh_.to_vertex_handle(h).idx()]);
  }
  bool eligible(HalfedgeHandle h, bool only_selected) const {
    const VertexHandle v0 = mesh_.from_vertex_handle(h);
    return !mesh_.status(mesh_.edge_handle(h)).deleted() && !mesh_.status(v0).deleted() &&
           (!only_selected || mesh_.status(v0).selected());
  }
  // What keeps a direction illegal until its neighbourhood changes; the full topological test
  // (collapse_legal: BaseDecimaterT::is_collapse_legal, answered without the library's assertions) is made
  // when the candidate is popped.
  bool may_collapse(HalfedgeHandle h, bool only_selected) const {
    if (!eligible(h, only_selected)) return false;
    const VertexHandle v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    return !mesh_.status(v0).locked() && (!mesh_.is_boundary(v0) || mesh_.is_boundary(v1));
  }
  // Prices the candidate \p slot with the priority module alone and queues it if legal.
  void price(int slot, bool only_selected) {
    HalfedgeHandle h = halfedge_of(slot);
    if (!may_collapse(h, only_selected)) {
      if (!by_edge_) return;
      h = halfedge_of(slot, 1);
      if (!may_collapse(h, only_selected)) return;
    }
    ++stats_.priced;
    const float key = priority_->collapse_priority(CollapseInfo(mesh_, h));
    if (key < 0.0f) return;
    heap_.push({key, slot, stamp_of(h)});
    queued_[slot] = 1;
    last_key_[slot] = key;
  }
  bool binary_modules_accept(const CollapseInfo& ci) {
    for (Module* m : binary_)
      if (m->collapse_priority(ci) < 0.0f) return false;
    return true;
  }
  // The direction of \p slot to collapse now, or an invalid handle when none is legal.
  HalfedgeHandle legal_direction(int slot, bool only_selected) {
    for (int dir = 0; dir < (by_edge_ ? 2 : 1); ++dir) {
      const HalfedgeHandle h = halfedge_of(slot, dir);
      if (by_edge_ && !may_collapse(h, only_selected)) continue;
      CollapseInfo ci(mesh_, h);
      if (collapse_legal(mesh_, ci) && binary_modules_accept(ci)) return h;
    }
    return HalfedgeHandle();
  }

  template <typename Continue>
  size_t run(bool only_selected, Continue go_on) {
    if (!this->is_initialized() || !priority_) return 0;
    for (Module* m : modules_)
      if (auto* b = dynamic_cast<BatchPricing*>(m)) b->price_all_edges(threads_);
    const size_t n_slots = by_edge_ ? mesh_.n_edges() : mesh_.n_halfedges();
    {
      // Room for every slot and the re-priced ones pushed on top, so that the heap does not grow by
      // doubling (a third of its memory unused, and old and new arrays side by side while it grows).
      heap_ = {};  // the last run's, freed before the new one is reserved
      std::vector<Candidate> storage;
      storage.reserve(n_slots + n_slots / 4);
      heap_ = std::priority_queue<Candidate>(std::less<Candidate>(), std::move(storage));
    }
    const auto* after = dynamic_cast<PriceAfterChecks*>(priority_);
    const bool price_after_checks = after && after->prices_after_checks();
    stamp_.assign(mesh_.n_vertices(), 0);
    queued_.assign(n_slots, 0);
    last_key_.assign(n_slots, 0.0f);
    clock_ = 0;
    for (size_t i = 0; i < n_slots; ++i) price(static_cast<int>(i), only_selected);

    size_t nv = mesh_.n_vertices(), nf = mesh_.n_faces(), done = 0;
    const bool update_normals = mesh_.has_face_normals();
    while (!heap_.empty() && go_on(done, nv, nf)) {
      const Candidate c = heap_.top();
      heap_.pop();
      queued_[c.slot] = 0;
      const HalfedgeHandle h0 = halfedge_of(c.slot);
      if (mesh_.status(mesh_.edge_handle(h0)).deleted()) continue;
      if (c.stamp != stamp_of(h0)) {
        ++stats_.stale;
        price(c.slot, only_selected);
        continue;
      }
      if (!by_edge_ && !eligible(h0, only_selected)) continue;
      const HalfedgeHandle h = legal_direction(c.slot, only_selected);
      if (!h.is_valid()) {
        ++stats_.refused;  // queued again when its neighbourhood changes
        continue;
      }
      CollapseInfo ci(mesh_, h);
      if (price_after_checks) {
        const float key = priority_->collapse_priority(ci);
        if (key < 0.0f) {
          ++stats_.refused;
          continue;
        }
        if (key > c.key && !heap_.empty() && key > heap_.top().key) {
          ++stats_.requeued;
          heap_.push({key, c.slot, c.stamp});
          queued_[c.slot] = 1;
          last_key_[c.slot] = key;
          continue;
        }
      }
      --nv;
      nf -= mesh_.is_boundary(ci.v0v1) || mesh_.is_boundary(ci.v1v0) ? 1 : 2;
      this->preprocess_collapse(ci);
      mesh_.collapse(h);
      if (update_normals)
        for (auto f : mesh_.vf_range(ci.v1)) mesh_.set_normal(f, mesh_.calc_face_normal(f));
      this->postprocess_collapse(ci);
      ++done;
      ++stats_.collapses;
      touch_around(ci.v1);
      if (!this->notify_observer(done)) break;
    }
    heap_ = {};
    for (Module* m : modules_)
      if (auto* b = dynamic_cast<BatchPricing*>(m)) b->end_of_run();
    return done;
  }

  // v1 and its ring now have other faces (v0's, or v1 moved): their candidates' keys and verdicts may be
  // out of date. Stamp them (only v1 when the priority module prices by the endpoints alone: verdicts are
  // asked at pop time anyway); candidates that had left the heap (refused, or illegal then) come back with
  // their last key (a lower bound when priorities only grow; 0 if never priced) and are re-priced when popped.
  void touch_around(VertexHandle v1) {
    ++clock_;
    stamp_[v1.idx()] = clock_;
    if (!endpoint_priority_)
      for (auto v : mesh_.vv_range(v1)) stamp_[v.idx()] = clock_;
    auto requeue = [&](HalfedgeHandle h) {
      const int slot = slot_of(h);
      if (!queued_[slot] && !mesh_.status(mesh_.edge_handle(h)).deleted()) {
        heap_.push({last_key_[slot], slot, 0});
        queued_[slot] = 1;
      }
    };
    auto requeue_at = [&](VertexHandle v) {
      for (auto h : mesh_.voh_range(v)) {
        requeue(h);
        if (!by_edge_) requeue(mesh_.opposite_halfedge_handle(h));
      }
    };
    requeue_at(v1);
    for (auto v : mesh_.vv_range(v1)) requeue_at(v);
  }

  Mesh& mesh_;
  std::vector<Module*> modules_, binary_;
  Module* priority_ = nullptr;
  bool endpoint_priority_ = false;  // the priority module says only v1's collapses change price
  bool by_edge_ = false;            // one candidate per edge (EdgePriority)
  int threads_ = std::max(1u, std::thread::hardware_concurrency());
  std::priority_queue<Candidate> heap_;
  std::vector<uint32_t> stamp_;
  std::vector<char> queued_;
  std::vector<float> last_key_;
  uint32_t clock_ = 0;
  LazyDecimaterStats stats_;
};

}  // namespace OpenMeshSkinned
