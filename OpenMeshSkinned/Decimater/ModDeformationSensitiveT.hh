#pragma once
/** \file ModDeformationSensitiveT.hh */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>

namespace OpenMeshSkinned {

/** Priority module: Mohr & Gleicher's Deformation Sensitive Decimation (as described by DeCoro &
 *  Rusinkiewicz, 2.2). The cost of collapsing v0 into v1 is the sum over the example poses of the
 *  per-pose quadrics (Q_v0 + Q_v1) evaluated at v1's posed position: endpoint placement, so the
 *  survivor keeps its position and skin (exactly OpenMesh's halfedge collapse). Both directions of an edge
 *  are priced, so the decimater takes the cheaper endpoint, as Mohr & Gleicher do. Units: squared length
 *  times area.
 */
template <typename MeshT>
class ModDeformationSensitiveT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModDeformationSensitiveT, MeshT, DeformationSensitive);

  explicit ModDeformationSensitiveT(MeshT& mesh) : Base(mesh, false) { solver_ = shared_solver(mesh, owns_property_); }
  ~ModDeformationSensitiveT() override {
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(Base::mesh());
  }

  void initialize() override { solver_->prepare(); }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    double e = 0.0;
    for (int j = 0; j < solver_->n_poses(); ++j) {
      PoseQuadric q = solver_->quadric(ci.v0, j);
      q += solver_->quadric(ci.v1, j);
      e += q(solver_->posed(ci.v1, j));
    }
    e = std::max(e, 0.0);
    if (e > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    return static_cast<float>(std::min<double>(e, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override { solver_->end_collapse(ci); }

  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }
  CollapseSolverT<MeshT>& solver() { return *solver_; }

private:
  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
  bool owns_property_ = false;
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
