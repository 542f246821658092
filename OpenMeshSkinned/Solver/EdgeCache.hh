#pragma once
/** \file EdgeCache.hh
 *  One answer per edge, valid while neither endpoint changes. DecimaterT re-prices every edge around a
 *  collapse, and most of those did not change: a vertex's version stamp moves on when it does.
 */

#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace OpenMeshSkinned {

class EdgeCache {
public:
  /// Joint indices are kept in 16 bits (a third of the cache's size went to padding and 32-bit joints).
  static constexpr int kMaxJoints = 65536;

  /** One slot per edge and a stamp per vertex, every slot empty. A slot holds at most \p capacity
   *  influences: the most an answer can have (the weight cap's n, when the solver places vertices itself;
   *  at 4 of 8 that is 40 bytes less per edge). A larger answer is not kept, so it is solved
   *  again when asked. */
  void reset(size_t n_edges, size_t n_vertices, int capacity = Influences::kCapacity) {
    capacity_ = std::clamp(capacity, 1, Influences::kCapacity);
    entries_.assign(n_edges, Entry{});
    weight_.assign(n_edges * capacity_, 0.0);
    joint_.assign(n_edges * capacity_, 0);
    stamp_.assign(n_vertices, 0);
  }
  /// The most influences an answer may have to be kept.
  int capacity() const { return capacity_; }
  /// Forgets every answer and makes the slots hold \p capacity influences (the cap changed). The vertex
  /// stamps are kept: they count the vertices' changes, which go on.
  void set_capacity(int capacity) {
    capacity_ = std::clamp(capacity, 1, Influences::kCapacity);
    invalidate();
    // New arrays rather than assign(), which would keep the larger ones' memory.
    std::vector<double>(entries_.size() * capacity_, 0.0).swap(weight_);
    std::vector<uint16_t>(entries_.size() * capacity_, 0).swap(joint_);
  }
  /// Forgets every answer (a setting changed).
  void invalidate() {
    for (auto& e : entries_) e.filled = false;
  }
  /// Vertex \p v changed: answers for its edges are stale.
  void touch(int v) { ++stamp_[v]; }
  /// How often \p v changed.
  uint32_t stamp(int v) const { return stamp_[v]; }

  /// Whether there is an answer for edge \p e between vertices \p a < \p b as they are.
  bool has(int e, int a, int b) const {
    const Entry& x = entries_[e];
    return x.filled && x.va == a && x.vb == b && x.sa == stamp_[a] && x.sb == stamp_[b];
  }
  /// Copies the answer for edge \p e between \p a < \p b into \p out; false when there is none for them as
  /// they are.
  bool find(int e, int a, int b, CollapseResult& out) const {
    if (!has(e, a, b)) return false;
    const Entry& x = entries_[e];
    out.position = x.position;
    out.error = x.error;
    out.area = x.area;
    out.valid = x.valid;
    out.weights.clear();
    const size_t slot = size_t(e) * capacity_;
    for (int i = 0; i < x.size; ++i) out.weights.push(joint_[slot + i], weight_[slot + i]);
    return true;
  }
  /// Keeps \p r as the answer for edge \p e between \p a < \p b.
  void store(int e, int a, int b, const CollapseResult& r) { store_solved(e, a, b, stamp_[a], stamp_[b], r); }

  /// As store(), with the stamps the answer was solved at (SolveAhead's worker, which must not read the
  /// stamps the mesh thread writes).
  void store_solved(int e, int a, int b, uint32_t sa, uint32_t sb, const CollapseResult& r) {
    Entry& x = entries_[e];
    if (r.weights.size() > capacity_) {
      x.filled = false;
      return;
    }
    x.position = r.position;
    x.error = r.error;
    x.area = r.area;
    x.valid = r.valid;
    x.size = static_cast<uint8_t>(r.weights.size());
    const size_t slot = size_t(e) * capacity_;
    for (int i = 0; i < r.weights.size(); ++i) {
      joint_[slot + i] = static_cast<uint16_t>(r.weights[i].joint);
      weight_[slot + i] = r.weights[i].weight;
    }
    x.va = a;
    x.vb = b;
    x.sa = sa;
    x.sb = sb;
    x.filled = true;
  }

private:
  // A CollapseResult without its padding, its influences in the slot arrays below (16-bit joints; the
  // weights stay doubles, so an answer read back is the answer solved).
  struct Entry {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double error = 0.0, area = 0.0;
    int va = -1, vb = -1;
    uint32_t sa = 0, sb = 0;
    uint8_t size = 0;
    bool valid = false, filled = false;
  };
  int capacity_ = Influences::kCapacity;
  std::vector<Entry> entries_;
  std::vector<double> weight_;
  std::vector<uint16_t> joint_;
  std::vector<uint32_t> stamp_;
};

}  // namespace OpenMeshSkinned
