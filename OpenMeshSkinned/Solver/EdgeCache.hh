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
  void reset(size_t n_edges, size_t n_vertices) {
    entries_.assign(n_edges, Entry{});
    stamp_.assign(n_vertices, 0);
  }
  /// Forgets every answer (a setting changed).
  void invalidate() {
    for (auto& e : entries_) e.filled = false;
  }
  /// Vertex \p v changed: answers for its edges are stale.
  void touch(int v) { ++stamp_[v]; }
  /// How often \p v changed.
  uint32_t stamp(int v) const { return stamp_[v]; }

  /// The answer for edge \p e between vertices \p a < \p b, or null when there is none for them as they are.
  const CollapseResult* find(int e, int a, int b) const {
    const Entry& x = entries_[e];
    return x.filled && x.va == a && x.vb == b && x.sa == stamp_[a] && x.sb == stamp_[b] ? &x.result : nullptr;
  }
  /// Where to put the answer for edge \p e between \p a < \p b, which is then valid.
  CollapseResult& store(int e, int a, int b) {
    Entry& x = entries_[e];
    x.va = a;
    x.vb = b;
    x.sa = stamp_[a];
    x.sb = stamp_[b];
    x.filled = true;
    return x.result;
  }

  /// As store(), with the stamps the answer was solved at (SolveAhead's worker, which must not read the
  /// stamps the mesh thread writes).
  CollapseResult& store_solved(int e, int a, int b, uint32_t sa, uint32_t sb) {
    Entry& x = entries_[e];
    x.va = a;
    x.vb = b;
    x.sa = sa;
    x.sb = sb;
    x.filled = true;
    return x.result;
  }

private:
  struct Entry {
    CollapseResult result;
    int va = -1, vb = -1;
    uint32_t sa = 0, sb = 0;
    bool filled = false;
  };
  std::vector<Entry> entries_;
  std::vector<uint32_t> stamp_;
};

}  // namespace OpenMeshSkinned
