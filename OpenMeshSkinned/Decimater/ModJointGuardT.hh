#pragma once
/** \file ModJointGuardT.hh */

#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <vector>

namespace OpenMeshSkinned {

/** Binary module: Savoye & Meyer's joint-region guard (2008, 4.2.2). With eta(k) the average weight of
 *  joint k over the vertices it influences (its non-zero weights), a vertex whose weight for some joint k
 *  is at least tau * eta(k) is ineligible: it may not disappear (a collapse v0 -> v1 is refused when v0 is
 *  ineligible). The paper's default tau = 1. Eligibility is decided once, on the skin as it is when the
 *  decimater initializes; it does not depend on the driver (DecimaterT or LazyDecimaterT).
 *
 *  \code
 *  OpenMeshSkinned::ModJointGuardT<Mesh>::Handle hg;
 *  dec.add(hg);
 *  dec.module(hg).set_tau(1.5);
 *  \endcode
 */
template <typename MeshT>
class ModJointGuardT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModJointGuardT, MeshT, JointGuard);

  explicit ModJointGuardT(MeshT& mesh) : Base(mesh, true) {}

  /// The threshold factor tau (> 0, default 1): larger guards fewer vertices.
  void set_tau(double tau) { tau_ = tau; }
  double tau() const { return tau_; }

  void initialize() override {
    const MeshT& mesh = Base::mesh();
    const auto h = influences_handle(mesh);
    // eta(k): the mean of joint k's non-zero weights.
    std::vector<double> sum, count;
    for (auto vh : mesh.vertices())
      for (const JointWeight& jw : mesh.property(h, vh)) {
        if (jw.weight <= 0.0) continue;
        if (static_cast<size_t>(jw.joint) >= sum.size()) sum.resize(jw.joint + 1, 0.0), count.resize(jw.joint + 1, 0.0);
        sum[jw.joint] += jw.weight;
        count[jw.joint] += 1.0;
      }
    eligible_.assign(mesh.n_vertices(), 1);
    for (auto vh : mesh.vertices())
      for (const JointWeight& jw : mesh.property(h, vh))
        if (jw.weight > 0.0 && jw.weight >= tau_ * sum[jw.joint] / count[jw.joint]) eligible_[vh.idx()] = 0;
  }

  /// Whether \p v may disappear (decided at initialize()).
  bool eligible(typename MeshT::VertexHandle v) const {
    return static_cast<size_t>(v.idx()) >= eligible_.size() || eligible_[v.idx()];
  }

  float collapse_priority(const CollapseInfo& ci) override {
    return eligible(ci.v0) ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

private:
  double tau_ = 1.0;
  std::vector<char> eligible_;
};

}  // namespace OpenMeshSkinned
