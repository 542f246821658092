#pragma once
/** \file SolverClient.hh
 *  What the shared collapse solver and the modules attached to it say to each other: the module's side
 *  (SolverClientT, EdgeModelT) and the solver's counters.
 */

#include "OpenMeshSkinned/Skin/Influences.hh"
#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"
#include "OpenMeshSkinned/Solver/SolverSettings.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <Eigen/Core>

#include <cstddef>

namespace OpenMeshSkinned {

struct CollapseSolverStats {
  size_t requests = 0;    ///< times a module asked for an edge
  size_t solves = 0;      ///< edges actually solved
  size_t cache_hits = 0;  ///< answered from the cache
  size_t collapses = 0;
  size_t placement_fallbacks = 0;  ///< collapses whose solved position was stale and was replaced
  size_t forced_flips = 0;         ///< collapses DecimaterT made although every placement flips a face
  size_t deferred = 0;             ///< vertices held back until DecimaterT re-asked them (stale verdicts)
  size_t fold_fallbacks = 0;       ///< collapses made at a fallback placement: the solved one folded (fold_fallback)
  WeightSolverStats weights;
};

/** A cost model other than the skinned quadric that places the merged vertex (e.g. the rest-pose
 *  quadric); the solver then caches and applies its answers. */
template <typename Mesh>
class EdgeModelT {
public:
  virtual ~EdgeModelT() = default;
  virtual void solve_edge(typename Mesh::VertexHandle a, typename Mesh::VertexHandle b, CollapseResult& out) = 0;
  /// Whether an answer also depends on the faces around the edge (then a collapse makes the answers of
  /// every edge around the surviving vertex's ring stale, not only of the edges at that vertex).
  virtual bool ring_dependent() const { return false; }
  /// The error of merging \p a and \p b at \p rest with skin \p w, in solve_edge()'s units; false when the
  /// model can price only its own placement (the fold check's fallback placements are then not offered).
  virtual bool error_at(typename Mesh::VertexHandle /*a*/, typename Mesh::VertexHandle /*b*/,
                        const Eigen::Vector3d& /*rest*/, const Influences& /*w*/, double& /*error*/) {
    return false;
  }
};

/// What a module attached to the solver asks of it (SolverModuleT implements it).
template <typename Mesh>
class SolverClientT {
public:
  virtual ~SolverClientT() = default;
  /// Adds this module's wishes to \p s.
  virtual void contribute(SolverSettings& s) const = 0;
  /// A placing module's own cost model, replacing the skinned quadric; null for the others.
  virtual EdgeModelT<Mesh>* edge_model() { return nullptr; }
  /// Once per collapse, when the solver has applied it (v1 placed and posed), before it re-judges the
  /// verdicts DecimaterT stored near v1: a module keeping state per face updates it here.
  virtual void collapse_applied(const OpenMesh::Decimater::CollapseInfoT<Mesh>&) {}
  /// Whether this module would now refuse a collapse it accepted when DecimaterT priced it (asked for the
  /// collapses stored near v1 after each collapse, with SolverSettings::recheck_stale; see StaleVerdictsT).
  virtual bool now_refuses(const OpenMesh::Decimater::CollapseInfoT<Mesh>&) { return false; }
};

}  // namespace OpenMeshSkinned
