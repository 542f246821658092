#pragma once
/** \file ModSkinnedQuadricT.hh */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>

namespace OpenMeshSkinned {

/** Priority module: the skinned quadric of Landreneau & Schaefer 2009.
 *
 *  The cost of collapsing an edge is the minimum, over the merged vertex's rest position and skin
 *  weights, of the quartic error summed over the mesh's example poses ("m:skin_poses"): how far the
 *  skinned vertex lies from the posed planes of the original faces it stands for, in every pose. Units:
 *  squared length times area (length^4) in the mesh's coordinates.
 *
 *  When a collapse happens, the surviving vertex moves to the optimal rest position and takes the
 *  optimal weights, its corner UVs (per-halfedge texcoords, when the mesh has them) are re-interpolated
 *  from the faces it came from, chart by chart, and its per-pose quadrics become the sums; the weights respect the cap set by
 *  ModWeightCapT if that module is present (otherwise the storage capacity, Influences::kCapacity).
 *
 *  \code
 *  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
 *  OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle hq;
 *  dec.add(hq);
 *  dec.module(hq).set_max_err(1e-3);  // optional tolerance
 *  \endcode
 */
template <typename MeshT>
class ModSkinnedQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModSkinnedQuadricT, MeshT, SkinnedQuadric);

  explicit ModSkinnedQuadricT(MeshT& mesh) : Base(mesh, false) {
    solver_ = shared_solver(mesh, owns_property_);
    solver_->set_placement(true);
  }
  ~ModSkinnedQuadricT() override {
    solver_->set_placement(false);
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(Base::mesh());
  }

  void initialize() override { solver_->prepare(); }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    const CollapseResult& r = solver_->solve(ci);
    if (!r.valid) return float(Base::ILLEGAL_COLLAPSE);
    if (r.error > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    solver_->note_legal_priority(ci, r.error);
    return static_cast<float>(std::min<double>(r.error, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override { solver_->end_collapse(ci); }

  /// Collapses whose error exceeds \p err (length^4 units, see class docs) are refused. Default: none.
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }
  void unset_max_err() { max_err_ = DBL_MAX; }

  /// Alternations of vertex and weight solves per edge at most (default 8; the error rarely falls after).
  void set_max_iterations(int n) { solver_->set_max_iterations(n); }
  int max_iterations() const { return solver_->max_iterations(); }

  /// The shared solver: settings, counters (solves, cache hits, Ceres calls).
  CollapseSolverT<MeshT>& solver() { return *solver_; }

private:
  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
  bool owns_property_ = false;
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
