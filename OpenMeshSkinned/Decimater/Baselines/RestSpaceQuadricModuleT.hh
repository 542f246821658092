#pragma once
/** \file RestSpaceQuadricModuleT.hh
 *  What ModRestPoseQuadricT and ModPoseIndependentQuadricT share: one static quadric per vertex in rest
 *  space, the merged vertex at its optimum, its skin by a weight-update rule. The two differ only in how
 *  they build the per-vertex quadrics (build_quadrics()).
 */

#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"
#include "OpenMeshSkinned/Solver/WeightRules.hh"

#include <cfloat>

namespace OpenMeshSkinned {

/// Priority-module base: static rest-space quadric, optimal placement, rule-based weights.
template <typename MeshT>
class RestSpaceQuadricModuleT : public SolverModuleT<MeshT>, private EdgeModelT<MeshT> {
  using ModBase = OpenMesh::Decimater::ModBaseT<MeshT>;

public:
  using CollapseInfo = typename ModBase::CollapseInfo;

  explicit RestSpaceQuadricModuleT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, false) { this->settings_changed(); }

  void initialize() override {
    SolverModuleT<MeshT>::initialize();
    h_inf_ = influences_handle(ModBase::mesh());
    quadric_.assign(ModBase::mesh().n_vertices(), PoseQuadric{});
    build_quadrics(quadric_);
  }

  /// The merged vertex is placed by the solve, whichever endpoint survives (EdgePriority).
  bool prices_edges() const override { return true; }

  void postprocess_collapse(const CollapseInfo& ci) override {
    quadric_[ci.v1.idx()] += quadric_[ci.v0.idx()];
    SolverModuleT<MeshT>::postprocess_collapse(ci);
  }

  /// How the merged vertex's skin is made (default DistanceInterpolation, DeCoro's rule).
  void set_weight_rule(WeightRule r) {
    rule_ = r;
    this->solver().invalidate_cache();
  }
  WeightRule weight_rule() const { return rule_; }
  /// Collapses above this error (squared length times area) are refused. Default: none.
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }

protected:
  /// Fills one quadric per vertex (indexed by vertex index), in rest-pose coordinates.
  virtual void build_quadrics(std::vector<PoseQuadric>& quadrics) = 0;
  OpenMesh::VPropHandleT<Influences> influences() const { return h_inf_; }

  float price(const CollapseInfo& ci) override {
    // The placement: a fold-over check that asked first may have moved it off the solved one.
    const CollapseResult& r = this->solver().placement(ci);
    if (!r.valid || r.error > max_err_ * ModBase::error_tolerance_factor_) return float(ModBase::ILLEGAL_COLLAPSE);
    this->solver().note_legal_priority(ci, r.error);
    return static_cast<float>(std::min<double>(r.error, FLT_MAX / 2));
  }
  void contribute(SolverSettings& s) const override { s.placement = true; }
  EdgeModelT<MeshT>* edge_model() override { return this; }

private:
  void solve_edge(typename MeshT::VertexHandle a, typename MeshT::VertexHandle b, CollapseResult& out) override {
    const MeshT& mesh = ModBase::mesh();
    PoseQuadric q = quadric_[a.idx()];
    q += quadric_[b.idx()];
    const Eigen::Vector3d pa = to_eigen(mesh.point(a)), pb = to_eigen(mesh.point(b));
    out.position = optimal_point(q, pa, pb);
    out.error = std::max(0.0, q(out.position));
    out.weights = merge_weights(rule_, out.position, pa, mesh.property(h_inf_, a), pb, mesh.property(h_inf_, b),
                                this->solver().max_influences());
    out.valid = out.position.allFinite();
  }
  bool error_at(typename MeshT::VertexHandle a, typename MeshT::VertexHandle b, const Eigen::Vector3d& rest,
                const Influences&, double& error) override {
    PoseQuadric q = quadric_[a.idx()];
    q += quadric_[b.idx()];
    error = std::max(0.0, q(rest));
    return true;
  }

  OpenMesh::VPropHandleT<Influences> h_inf_;
  std::vector<PoseQuadric> quadric_;
  WeightRule rule_ = WeightRule::DistanceInterpolation;
  double max_err_ = DBL_MAX;
};

}  // namespace OpenMeshSkinned
