#pragma once
/** \file ModWeightCapT.hh */

#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"

#include <algorithm>

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
class ModWeightCapT : public SolverModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModWeightCapT, MeshT, WeightCap);

  explicit ModWeightCapT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, true) { this->settings_changed(); }

  void initialize() override {
    SolverModuleT<MeshT>::initialize();
    reduced_ = reduce_input_ ? this->solver().reduce_input_influences() : 0;
  }

  /// Most influences per vertex, 1..Influences::kCapacity (default 4).
  void set_max_influences(int n) {
    max_influences_ = std::clamp(n, 1, Influences::kCapacity);
    this->settings_changed();
  }
  int max_influences() const { return max_influences_; }

  /// How the cap is met when the optimum uses more joints (default CapStrategy::Greedy: it kept the posed
  /// surface closer than the paper's TopN on every real test character and cap, see bench/README.md,
  /// "omsk-bench: the papers' workloads").
  void set_strategy(CapStrategy s) {
    strategy_ = s;
    this->settings_changed();
  }
  CapStrategy strategy() const { return strategy_; }

  /// Whether initialize() reduces input vertices above the cap (default true).
  void set_reduce_input(bool on) { reduce_input_ = on; }
  bool reduce_input() const { return reduce_input_; }

  /// Input vertices reduced by the last initialize().
  size_t reduced_vertices() const { return reduced_; }

protected:
  float price(const CollapseInfo& ci) override {
    Eigen::Vector3d rest;
    Influences w;
    this->solver().placement_of(ci, rest, w);
    return w.size() <= max_influences_ ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }
  void contribute(SolverSettings& s) const override {
    s.max_influences = std::min(s.max_influences, max_influences_);
    s.strategy = strategy_;
  }

private:
  int max_influences_ = 4;
  CapStrategy strategy_ = SolveSettings{}.strategy;
  bool reduce_input_ = true;
  size_t reduced_ = 0;
};

}  // namespace OpenMeshSkinned
