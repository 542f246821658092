#pragma once
/** \file ModWeightCapT.hh */

#include "OpenMeshSkinned/Solver/CollapseSolverT.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

namespace OpenMeshSkinned {

/** Binary module: at most n bone influences on every vertex of every level (GPU skinning budgets).
 *
 *  At initialize(), input vertices with more than n influences are reduced by the weight solve on their
 *  own quadrics (not by truncation), unless set_reduce_input(false). During decimation the shared solver
 *  is told the cap, so the skinned quadric's merged vertices come out within it; a collapse whose
 *  surviving vertex would still carry more than n influences (possible only when the input was left
 *  unreduced and no module places vertices) is refused.
 *
 *  \code
 *  OpenMeshSkinned::ModWeightCapT<Mesh>::Handle hc;
 *  dec.add(hc);
 *  dec.module(hc).set_max_influences(4);
 *  \endcode
 */
template <typename MeshT>
class ModWeightCapT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModWeightCapT, MeshT, WeightCap);

  explicit ModWeightCapT(MeshT& mesh) : Base(mesh, true) {
    solver_ = shared_solver(mesh, owns_property_);
    solver_->set_max_influences(4);
  }
  ~ModWeightCapT() override {
    solver_->set_max_influences(Influences::kCapacity);
    solver_->release_deferred();
    if (owns_property_) release_shared_solver(Base::mesh());
  }

  void initialize() override {
    solver_->prepare();
    reduced_ = reduce_input_ ? solver_->reduce_input_influences() : 0;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    solver_->begin_pricing(ci);
    Eigen::Vector3d rest;
    Influences w;
    solver_->placement_of(ci, rest, w);
    return w.size() <= solver_->max_influences() ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

  void preprocess_collapse(const CollapseInfo& ci) override { solver_->begin_collapse(ci); }
  void postprocess_collapse(const CollapseInfo& ci) override { solver_->end_collapse(ci); }

  /// Most influences per vertex, 1..Influences::kCapacity (default 4).
  void set_max_influences(int n) { solver_->set_max_influences(n); }
  int max_influences() const { return solver_->max_influences(); }

  /// How the cap is met when the optimum uses more joints (default CapStrategy::TopN, the paper's; it kept
  /// the posed surface closer than Greedy on the real test characters, see bench/README.md).
  void set_strategy(CapStrategy s) { solver_->set_cap_strategy(s); }
  CapStrategy strategy() const { return solver_->cap_strategy(); }

  /// Whether initialize() reduces input vertices above the cap (default true).
  void set_reduce_input(bool on) { reduce_input_ = on; }
  bool reduce_input() const { return reduce_input_; }

  /// Input vertices reduced by the last initialize().
  size_t reduced_vertices() const { return reduced_; }

  /// The shared solver: settings and counters.
  CollapseSolverT<MeshT>& solver() { return *solver_; }

private:
  std::shared_ptr<CollapseSolverT<MeshT>> solver_;
  bool owns_property_ = false;
  bool reduce_input_ = true;
  size_t reduced_ = 0;
};

}  // namespace OpenMeshSkinned
