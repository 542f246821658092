#pragma once
/** \file LazyDecimaterT.hh */

#include "OpenMeshSkinned/Decimater/DriverHints.hh"

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>

#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <queue>
#include <thread>
#include <vector>

namespace OpenMeshSkinned {

struct LazyDecimaterStats {
  size_t priced = 0;   ///< priority module calls
  size_t stale = 0;    ///< popped candidates whose neighbourhood had changed, re-priced and pushed back
  size_t refused = 0;  ///< popped candidates a binary module or the topology refused
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
 *  Modules implementing BatchPricing compute their answers for all edges first on set_threads() threads.
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
    return priority_ != nullptr;
  }

  /// Threads for modules that price all edges ahead (BatchPricing); default: the hardware's.
  void set_threads(int n) { threads_ = std::max(1, n); }
  int threads() const { return threads_; }

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
  struct Candidate {
    float key;
    int h;
    uint32_t stamp;
    // A min-heap on (key, halfedge index): ties resolve the same way on every run.
    bool operator<(const Candidate& o) const { return key != o.key ? key > o.key : h > o.h; }
  };

  uint32_t stamp_of(HalfedgeHandle h) const {
    return std::max(stamp_[mesh_.from_vertex_handle(h).idx()], stamp_[mesh_.to_vertex_handle(h).idx()]);
  }
  bool eligible(HalfedgeHandle h, bool only_selected) const {
    const VertexHandle v0 = mesh_.from_vertex_handle(h);
    return !mesh_.status(mesh_.edge_handle(h)).deleted() && !mesh_.status(v0).deleted() &&
           (!only_selected || mesh_.status(v0).selected());
  }
  // Prices \p h with the priority module alone and queues it if legal.
  void price(HalfedgeHandle h) {
    const CollapseInfo ci(mesh_, h);
    // The full topological test (is_collapse_legal, a quarter of the run) is made when the candidate is
    // popped; here only what keeps a candidate illegal until its neighbourhood changes.
    if (mesh_.status(ci.v0).locked() || (mesh_.is_boundary(ci.v0) && !mesh_.is_boundary(ci.v1))) return;
    ++stats_.priced;
    const float key = priority_->collapse_priority(ci);
    if (key < 0.0f) return;
    heap_.push({key, h.idx(), stamp_of(h)});
    queued_[h.idx()] = 1;
    last_key_[h.idx()] = key;
  }
  bool binary_modules_accept(const CollapseInfo& ci) {
    for (Module* m : binary_)
      if (m->collapse_priority(ci) < 0.0f) return false;
    return true;
  }

  template <typename Continue>
  size_t run(bool only_selected, Continue go_on) {
    if (!this->is_initialized() || !priority_) return 0;
    for (Module* m : modules_)
      if (auto* b = dynamic_cast<BatchPricing*>(m)) b->price_all_edges(threads_);
    heap_ = {};
    stamp_.assign(mesh_.n_vertices(), 0);
    queued_.assign(mesh_.n_halfedges(), 0);
    last_key_.assign(mesh_.n_halfedges(), 0.0f);
    clock_ = 0;
    for (auto h : mesh_.halfedges())
      if (eligible(h, only_selected)) price(h);

    size_t nv = mesh_.n_vertices(), nf = mesh_.n_faces(), done = 0;
    const bool update_normals = mesh_.has_face_normals();
    while (!heap_.empty() && go_on(done, nv, nf)) {
      const Candidate c = heap_.top();
      heap_.pop();
      const HalfedgeHandle h(c.h);
      queued_[c.h] = 0;
      if (!eligible(h, only_selected)) continue;
      if (c.stamp != stamp_of(h)) {
        ++stats_.stale;
        price(h);
        continue;
      }
      CollapseInfo ci(mesh_, h);
      if (!this->is_collapse_legal(ci) || !binary_modules_accept(ci)) {
        ++stats_.refused;  // queued again when its neighbourhood changes
        continue;
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
      touch_around(ci.v1, only_selected);
      if (!this->notify_observer(done)) break;
    }
    heap_ = {};
    return done;
  }

  // v1 and its ring now have other faces (v0's, or v1 moved): their candidates' keys and verdicts may be
  // out of date. Stamp them (only v1 when the priority module prices by the endpoints alone: verdicts are
  // asked at pop time anyway); candidates that had left the heap (refused, or illegal then) come back with
  // their last key (a lower bound when priorities only grow; 0 if never priced) and are re-priced when popped.
  void touch_around(VertexHandle v1, bool only_selected) {
    ++clock_;
    stamp_[v1.idx()] = clock_;
    if (!endpoint_priority_)
      for (auto v : mesh_.vv_range(v1)) stamp_[v.idx()] = clock_;
    auto requeue = [&](HalfedgeHandle h) {
      if (!queued_[h.idx()] && eligible(h, only_selected)) {
        heap_.push({last_key_[h.idx()], h.idx(), 0});
        queued_[h.idx()] = 1;
      }
    };
    for (auto h : mesh_.voh_range(v1)) requeue(h), requeue(mesh_.opposite_halfedge_handle(h));
    for (auto v : mesh_.vv_range(v1))
      for (auto h : mesh_.voh_range(v)) requeue(h), requeue(mesh_.opposite_halfedge_handle(h));
  }

  Mesh& mesh_;
  std::vector<Module*> modules_, binary_;
  Module* priority_ = nullptr;
  bool endpoint_priority_ = false;  // the priority module says only v1's collapses change price
  int threads_ = std::max(1u, std::thread::hardware_concurrency());
  std::priority_queue<Candidate> heap_;
  std::vector<uint32_t> stamp_;
  std::vector<char> queued_;
  std::vector<float> last_key_;
  uint32_t clock_ = 0;
  LazyDecimaterStats stats_;
};

}  // namespace OpenMeshSkinned
