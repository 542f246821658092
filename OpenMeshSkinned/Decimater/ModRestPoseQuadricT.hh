#pragma once
/** \file ModRestPoseQuadricT.hh */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"
#include "OpenMeshSkinned/Solver/WeightRules.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>

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
class ModRestPoseQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT>, private EdgeModelT<MeshT> {
public:
  DECIMATING_MODULE(ModRestPoseQuadricT, MeshT, RestPoseQuadric);

  explicit ModRestPoseQuadricT(MeshT& mesh) : Base(mesh, false) {
    solver_ = shared_solver(mesh, owns_property_);
    solver_->set_placement(true);
    solver_->set_edge_model(this);
  }
  ~ModRestPoseQuadricT() override {
    solver_->set_edge_model(nullptr);
    solver_->set_placement(false);
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(Base::mesh());
  }

  void initialize() override {
    solver_->prepare();
    h_inf_ = influences_handle(Base::mesh());
    quadric_.assign(Base::mesh().n_vertices(), PoseQuadric{});
    accumulate_quadrics(
        Base::mesh(), 1, [this](typename MeshT::VertexHandle v, int) { return to_eigen(Base::mesh().point(v)); },
        [this](typename MeshT::VertexHandle v, int) -> PoseQuadric& { return quadric_[v.idx()]; });
  }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    const CollapseResult& r = solver_->solve(ci);
    if (!r.valid || r.error > max_err_ * Base::error_tolerance_factor_) return float(Base::ILLEGAL_COLLAPSE);
    solver_->note_legal_priority(ci, r.error);
    return static_cast<float>(std::min<double>(r.error, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override {
    quadric_[ci.v1.idx()] += quadric_[ci.v0.idx()];
    solver_->end_collapse(ci);
  }

  void set_weight_rule(WeightRule r) {
    rule_ = r;
    solver_->invalidate_cache();
  }
  WeightRule weight_rule() const { return rule_; }
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }
  CollapseSolverT<MeshT>& solver() { return *solver_; }

private:
  void solve_edge(typename MeshT::VertexHandle a, typename MeshT::VertexHandle b, CollapseResult& out) override {
    PoseQuadric q = quadric_[a.idx()];
    q += quadric_[b.idx()];
    const Eigen::Vector3d pa = to_eigen(Base::mesh().point(a)), pb = to_eigen(Base::mesh().point(b));
    out.position = optimal_point(q, pa, pb);
    out.error = std::max(0.0, q(out.position));
    out.weights = merge_weights(rule_, out.position, pa, Base::mesh().property(h_inf_, a), pb,
                                Base::mesh().property(h_inf_, b), solver_->max_influences());
    out.valid = out.position.allFinite();
  }

  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
  bool owns_property_ = false;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  std::vector<PoseQuadric> quadric_;
  WeightRule rule_ = WeightRule::DistanceInterpolation;
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
