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
    // v1 stays where it is, with its skin.
    const MeshT& mesh = Base::mesh();
    const double e =
        this->solver().error_at(ci, to_eigen(mesh.point(ci.v1)), mesh.property(influences_handle(mesh), ci.v1));
    if (e > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    return static_cast<float>(std::min<double>(e, FLT_MAX / 2));
  }

private:
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
