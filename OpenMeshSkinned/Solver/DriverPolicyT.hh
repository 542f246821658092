#pragma once
/** \file DriverPolicyT.hh
 *  What the shared solver does differently for the two kinds of decimater driver.
 *
 *  A driver that asks binary modules right before each collapse (LazyDecimaterT, checks_at_pop()) never
 *  acts on a stale verdict, and asks the priority module alone when pricing: the solver then has nothing
 *  to keep track of, and this base class is its policy. OpenMesh's DecimaterT stores verdicts and acts on
 *  them later: StaleVerdictPolicyT.hh is its policy.
 */

#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

namespace OpenMeshSkinned {

template <typename Mesh>
class DriverPolicyT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  virtual ~DriverPolicyT() = default;
  /// Whether this is the policy of a driver that asks binary modules at pop time.
  virtual bool checks_at_pop() const { return true; }
  /// Once per decimation, after the solver's tables are built.
  virtual void prepare() {}
  /// Every pricing of a collapse starts here.
  virtual void begin_pricing(const CollapseInfo&) {}
  /// The priority module reports a collapse that every binary module accepted, with its cost.
  virtual void note_legal(const CollapseInfo&, double /*error*/) {}
  /// Whether \p ci cannot win over a legal collapse already priced for the same v0 (its checks can be skipped).
  virtual bool cannot_win(const CollapseInfo&) { return false; }
  /// Before the collapse of \p ci (the mesh as it was).
  virtual void before_collapse(const CollapseInfo&) {}
  /// The placement \p pending the collapse of \p ci is about to use: replaced when it is stale.
  virtual void check_placement(const CollapseInfo&, CollapseResult& /*pending*/) {}
  /// After the collapse into \p v1 was applied and the modules were told.
  virtual void after_collapse(VertexHandle /*v1*/) {}
  /// Undoes what the policy did to the mesh (vertex locks).
  virtual void release() {}
};

}  // namespace OpenMeshSkinned
