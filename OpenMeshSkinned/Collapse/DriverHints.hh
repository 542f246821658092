#pragma once
/** \file DriverHints.hh
 *  What a decimater driver tells the modules, and what a module offers a driver, beyond ModBaseT.
 *
 *  OpenMesh's DecimaterT asks binary modules when it prices a collapse and never again; LazyDecimaterT asks
 *  them when it pops one. A module that works around stale verdicts (the shared solver's deferral) must
 *  know which driver it is in: the driver says so with a named mesh property, since ModBaseT has no hook.
 */

#include <OpenMesh/Core/Utils/Property.hh>

namespace OpenMeshSkinned {

/// Named mesh property (bool), present and true while a driver asks binary modules at pop time.
inline constexpr const char* kChecksAtPopProperty = "m:omsk_checks_at_pop";

/// Whether the driver decimating \p mesh asks binary modules right before each collapse.
template <typename Mesh>
bool checks_at_pop(const Mesh& mesh) {
  OpenMesh::MPropHandleT<bool> h;
  return mesh.get_property_handle(h, kChecksAtPopProperty) && mesh.property(h);
}

/// Sets or clears the mark checks_at_pop() reads (the property is removed when cleared).
template <typename Mesh>
void set_checks_at_pop(Mesh& mesh, bool on) {
  OpenMesh::MPropHandleT<bool> h;
  const bool has = mesh.get_property_handle(h, kChecksAtPopProperty);
  if (on) {
    if (!has) mesh.add_property(h, kChecksAtPopProperty);
    mesh.property(h) = true;
  } else if (has) {
    mesh.remove_property(h);
  }
}

/** A module that can compute the answers for every edge ahead of the driver's first pricing pass, on
 *  several threads, with answers that do not depend on the thread count. The driver still asks it edge by
 *  edge afterwards; the module answers from what it computed. */
class BatchPricing {
public:
  virtual ~BatchPricing() = default;
  virtual void price_all_edges(int threads) = 0;
  /// The driver's run is over (a module may stop threads it started for it).
  virtual void end_of_run() {}
};

/** A priority module whose price of a collapse depends only on its two endpoints (their positions and
 *  whatever the module keeps per vertex), not on the faces around them: a driver then needs to re-price
 *  only the collapses touching the vertex a collapse changed, not those of its whole ring. Binary
 *  modules are not concerned (LazyDecimaterT asks them right before each collapse). */
class EndpointPriority {
public:
  virtual ~EndpointPriority() = default;
  /// False for a module of this family whose prices look at the faces around the endpoints after all.
  virtual bool prices_by_endpoints() const { return true; }
};

/** A priority module that prices both halfedges of an edge alike (it places the merged vertex itself, so
 *  the collapse's outcome does not depend on which endpoint survives): a driver may then keep one candidate
 *  per edge instead of two, half the queue and half the re-pricing. */
class EdgePriority {
public:
  virtual ~EdgePriority() = default;
  virtual bool prices_edges() const { return false; }
};

/** A priority module whose price of a collapse may change once the binary modules have accepted it: the
 *  fold-over check may have moved the merged vertex off its solved placement, to one that folds nothing
 *  (ModSkinnedFoldOverT::set_fallback_placement). A driver that asks binary modules at pop time then asks
 *  the priority module again, and queues the candidate again if it is no longer the cheapest. */
class PriceAfterChecks {
public:
  virtual ~PriceAfterChecks() = default;
  virtual bool prices_after_checks() const { return false; }
};

}  // namespace OpenMeshSkinned
