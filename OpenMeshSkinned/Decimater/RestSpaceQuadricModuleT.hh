#pragma once
/** \file RestSpaceQuadricModuleT.hh
 *  What ModRestPoseQuadricT and ModPoseIndependentQuadricT share: one static quadric per vertex in rest
 *  space, the merged vertex at its optimum, its skin by a weight-update rule. The two differ only in how
 *  they build the per-vertex quadrics (build_quadrics()).
 */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"
#include "OpenMeshSkinned/Solver/WeightRules.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <cfloat>

namespace OpenMeshSkinned {

/// Priority-module base: static rest-space quadric, optimal placement, rule-based weights.
template <typename MeshT>
class RestSpaceQuadricModuleT : public OpenMesh::Decimater::ModBaseT<MeshT>, private EdgeModelT<MeshT> {
  using ModBase = OpenMesh::Decimater::ModBaseT<MeshT>;

public:
  using CollapseInfo = typename ModBase::CollapseInfo;

  explicit RestSpaceQuadricModuleT(MeshT& mesh) : ModBase(mesh, false) {
    solver_ = shared_solver(mesh, owns_property_);
    solver_->set_placement(true);
    solver_->set_edge_model(this);
  }
  ~RestSpaceQuadricModuleT() override {
    solver_->set_edge_model(nullptr);
    solver_->set_placement(false);
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(ModBase::mesh());
  }

  void initialize() override {
    solver_->prepare();
    h_inf_ = influences_handle(ModBase::mesh());
    quadric_.assign(ModBase::mesh().n_vertices(), PoseQuadric{});
    build_quadrics(quadric_);
  }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    const CollapseResult& r = solver_->solve(ci);
    if (!r.valid || r.error > max_err_ * ModBase::error_tolerance_factor_) return float(ModBase::ILLEGAL_COLLAPSE);
    solver_->note_legal_priority(ci, r.error);
    return static_cast<float>(std::min<double>(r.error, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override {
    quadric_[ci.v1.idx()] += quadric_[ci.v0.idx()];
    solver_->end_collapse(ci);
  }

  /// How the merged vertex's skin is made (default DistanceInterpolation, DeCoro's rule).
  void set_weight_rule(WeightRule r) {
    rule_ = r;
    solver_->invalidate_cache();
  }
  WeightRule weight_rule() const { return rule_; }
  /// Collapses above this error (squared length times area) are refused. Default: none.
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }
  CollapseSolverT<MeshT>& solver() { return *solver_; }

protected:
  /// Fills one quadric per vertex (indexed by vertex index), in rest-pose coordinates.
  virtual void build_quadrics(std::vector<PoseQuadric>& quadrics) = 0;
  OpenMesh::VPropHandleT<Influences> influences() const { return h_inf_; }

private:
  void solve_edge(typename MeshT::VertexHandle a, typename MeshT::VertexHandle b, CollapseResult& out) override {
    const MeshT& mesh = ModBase::mesh();
    PoseQuadric q = quadric_[a.idx()];
    q += quadric_[b.idx()];
    const Eigen::Vector3d pa = to_eigen(mesh.point(a)), pb = to_eigen(mesh.point(b));
    out.position = optimal_point(q, pa, pb);
    out.error = std::max(0.0, q(out.position));
    out.weights = merge_weights(rule_, out.position, pa, mesh.property(h_inf_, a), pb, mesh.property(h_inf_, b),
                                solver_->max_influences());
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
