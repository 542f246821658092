#pragma once
/** \file ModRestPoseQuadricT.hh */

#include "OpenMeshSkinned/Decimater/Baselines/RestSpaceQuadricModuleT.hh"

namespace OpenMeshSkinned {

/** Priority module: the industry baseline. Garland-Heckbert quadric of the bind pose only (the mesh as
 *  stored), the merged vertex at the quadric's optimum, its skin by a weight-update rule (default
 *  DistanceInterpolation; see WeightRules.hh). What rest-pose LOD tools do; a reference for the skinned
 *  quadric. Units: squared length times area in the mesh's coordinates.
 *
 *  Works with ModWeightCapT (the rule's blend is truncated to the cap) and ModSkinnedFoldOverT (which
 *  checks this module's placement in every example pose).
 */
template <typename MeshT>
class ModRestPoseQuadricT : public RestSpaceQuadricModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModRestPoseQuadricT, MeshT, RestPoseQuadric);

  explicit ModRestPoseQuadricT(MeshT& mesh) : RestSpaceQuadricModuleT<MeshT>(mesh) {}

protected:
  void build_quadrics(std::vector<PoseQuadric>& quadrics) override {
    const MeshT& mesh = Base::mesh();
    accumulate_quadrics(
        mesh, 1, [&](typename MeshT::VertexHandle v, int) { return to_eigen(mesh.point(v)); },
        [&](typename MeshT::VertexHandle v, int) -> PoseQuadric& { return quadrics[v.idx()]; });
  }
};

}  // namespace OpenMeshSkinned
