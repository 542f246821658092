// Pins what the shared solver assumes of OpenMesh's DecimaterT (listed in Decimater/SolverModuleT.hh):
// spy modules record every call a real DecimaterT makes while decimating a small mesh. If an OpenMesh
// release changes any of this, the solver's pricing shortcuts and deferral must be revisited.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <set>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

struct Call {
  enum Kind { Price, Pre, Post } kind;
  int module;  // 0, 1: binary spies; 2: the priority spy
  int v0, v1;
  float answer;
  std::set<int> ring;  // Pre: v0's neighbours before the collapse
};
std::vector<Call> g_log;

template <typename MeshT>
class SpyT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(SpyT, MeshT, Spy);
  explicit SpyT(MeshT& mesh) : Base(mesh, true) {}
  void setup(int id, bool binary) {
    id_ = id;
    this->set_binary(binary);
  }
  float collapse_priority(const CollapseInfo& ci) override {
    float answer;
    if (this->is_binary()) {
      // Each binary spy refuses a different, deterministic share of collapses.
      answer = (ci.v0.idx() + ci.v1.idx() + id_) % 4 == 0 ? float(Base::ILLEGAL_COLLAPSE) : float(Base::LEGAL_COLLAPSE);
    } else {
      answer = float((ci.p1 - ci.p0).sqrnorm());
    }
    g_log.push_back({Call::Price, id_, ci.v0.idx(), ci.v1.idx(), answer, {}});
    return answer;
  }
  void preprocess_collapse(const CollapseInfo& ci) override {
    Call c{Call::Pre, id_, ci.v0.idx(), ci.v1.idx(), 0, {}};
    for (auto vh : this->mesh().vv_range(ci.v0)) c.ring.insert(vh.idx());
    g_log.push_back(c);
  }
  void postprocess_collapse(const CollapseInfo& ci) override {
    g_log.push_back({Call::Post, id_, ci.v0.idx(), ci.v1.idx(), 0, {}});
  }

private:
  int id_ = 0;
};

// Two spies must be distinct module types for DecimaterT (it keeps one module per handle, any type).
template <typename MeshT>
class SpyBT : public SpyT<MeshT> {
public:
  using SpyT<MeshT>::SpyT;
};

struct SpyRun {
  std::vector<Call> log;
  size_t collapses = 0;
  Mesh mesh;
  std::set<int> locked_v0_collapsed;
};

SpyRun decimate_with_spies(bool lock_some) {
  SpyRun r;
  r.mesh = make_bending_cylinder(8, 12);
  Mesh& mesh = r.mesh;
  std::set<int> locked;
  if (lock_some)
    for (auto vh : mesh.vertices())
      if (vh.idx() % 7 == 3) {
        mesh.status(vh).set_locked(true);
        locked.insert(vh.idx());
      }
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  typename SpyT<Mesh>::Handle b0;
  typename SpyBT<Mesh>::Handle b1;
  typename SpyT<Mesh>::Handle pr;
  dec.add(b0);
  dec.add(b1);
  dec.add(pr);
  dec.module(b0).setup(0, true);
  dec.module(b1).setup(1, true);
  dec.module(pr).setup(2, false);
  EXPECT_TRUE(dec.initialize());
  g_log.clear();
  r.collapses = dec.decimate_to(mesh.n_vertices() / 2);
  r.log = g_log;
  for (const Call& c : r.log)
    if (c.kind == Call::Pre && locked.count(c.v0)) r.locked_v0_collapsed.insert(c.v0);
  return r;
}

}  // namespace

TEST(DecimaterContract, BinaryModulesFirstInOrderThePriorityModuleOnlyWhenAllAccept) {
  const SpyRun r = decimate_with_spies(false);
  ASSERT_GT(r.collapses, 10u);
  for (size_t i = 0; i < r.log.size(); ++i) {
    const Call& c = r.log[i];
    if (c.kind != Call::Price || c.module != 2) continue;
    ASSERT_GE(i, 2u);
    const Call &a = r.log[i - 2], &b = r.log[i - 1];
    EXPECT_TRUE(a.kind == Call::Price && a.module == 0 && a.v0 == c.v0 && a.v1 == c.v1 && a.answer >= 0) << i;
    EXPECT_TRUE(b.kind == Call::Price && b.module == 1 && b.v0 == c.v0 && b.v1 == c.v1 && b.answer >= 0) << i;
  }
  // And a binary refusal ends the pricing of that collapse.
  for (size_t i = 0; i + 1 < r.log.size(); ++i) {
    if (r.log[i].kind == Call::Price && r.log[i].module == 0 && r.log[i].answer < 0) {
      EXPECT_FALSE(r.log[i + 1].kind == Call::Price && r.log[i + 1].v0 == r.log[i].v0 &&
                   r.log[i + 1].v1 == r.log[i].v1);
    }
  }
}

TEST(DecimaterContract, AVertexIsPricedInOneUninterruptedSweep) {
  const SpyRun r = decimate_with_spies(false);
  // Between two collapses, each v0 forms one contiguous run of pricing calls.
  std::set<int> done;
  int current = -1;
  for (const Call& c : r.log) {
    if (c.kind != Call::Price) {
      done.clear();
      current = -1;
      continue;
    }
    if (c.v0 != current) {
      EXPECT_FALSE(done.count(c.v0)) << "vertex " << c.v0 << " priced again within the same sweep phase";
      if (current >= 0) done.insert(current);
      current = c.v0;
    }
  }
}

TEST(DecimaterContract, EveryModuleSeesEachCollapseOnceBinaryFirstAndOnlyV0sRingIsRepriced) {
  const SpyRun r = decimate_with_spies(false);
  size_t pre = 0;
  for (size_t i = 0; i < r.log.size(); ++i) {
    if (r.log[i].kind != Call::Pre || r.log[i].module != 0) continue;
    ++pre;
    ASSERT_LT(i + 5, r.log.size() + 1);
    const int v0 = r.log[i].v0, v1 = r.log[i].v1;
    const Call::Kind kinds[] = {Call::Pre, Call::Pre, Call::Pre, Call::Post, Call::Post, Call::Post};
    const int modules[] = {0, 1, 2, 0, 1, 2};
    for (int k = 0; k < 6; ++k) {
      ASSERT_LT(i + k, r.log.size());
      EXPECT_EQ(r.log[i + k].kind, kinds[k]);
      EXPECT_EQ(r.log[i + k].module, modules[k]);
      EXPECT_EQ(r.log[i + k].v0, v0);
      EXPECT_EQ(r.log[i + k].v1, v1);
    }
    // Re-pricing after the collapse: v0's former neighbours only (v1 among them), never v0 itself.
    for (size_t k = i + 6; k < r.log.size() && r.log[k].kind == Call::Price; ++k)
      EXPECT_TRUE(r.log[i].ring.count(r.log[k].v0)) << "vertex " << r.log[k].v0 << " is outside v0's ring";
  }
  EXPECT_EQ(pre, r.collapses);
}

TEST(DecimaterContract, ALockedVertexIsNeverCollapsedAway) {
  const SpyRun r = decimate_with_spies(true);
  ASSERT_GT(r.collapses, 10u);
  EXPECT_TRUE(r.locked_v0_collapsed.empty());
}
