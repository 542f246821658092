#pragma once
/** \file ModDeformationSensitiveT.hh */

#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"

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
class ModDeformationSensitiveT : public SolverModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModDeformationSensitiveT, MeshT, DeformationSensitive);

  explicit ModDeformationSensitiveT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, false) {}

  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }

protected:
  float price(const CollapseInfo& ci) override {
    const auto& solver = this->solver();
    double e = 0.0;
    for (int j = 0; j < solver.n_poses(); ++j) {
      PoseQuadric q = solver.quadric(ci.v0, j);
      q += solver.quadric(ci.v1, j);
      e += q(solver.posed(ci.v1, j));
    }
    e = std::max(e, 0.0);
    if (e > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    return static_cast<float>(std::min<double>(e, FLT_MAX / 2));
  }

private:
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
