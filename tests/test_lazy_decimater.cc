// LazyDecimaterT: DecimaterT's interface and results, binary modules asked right before each collapse,
// answers that do not depend on the thread count.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using Lazy = LazyDecimaterT<Mesh>;

namespace {

size_t live_faces(const Mesh& m) {
  size_t n = 0;
  for (auto f : m.faces()) (void)f, ++n;
  return n;
}

// Mean RMS distance over a mesh's example poses (fraction of the diagonal).
double mean_posed_rms(const Mesh& original, const Mesh& lod) {
  double sum = 0.0;
  for (const auto& pose : example_poses(original)) sum += omsk_test::posed_rms(original, lod, pose);
  return sum / example_poses(original).size();
}

// Held-out frames: the clip sampled between the example poses.
double held_out_rms(const Mesh& original, const Mesh& lod) {
  const auto frames = sample_poses_evenly(skeleton(original), clips(original)[0], 7);
  double sum = 0.0;
  for (const auto& pose : frames) sum += omsk_test::posed_rms(original, lod, pose);
  return sum / frames.size();
}

template <typename Decimater>
size_t static_decimate(Mesh& mesh, size_t faces) {
  Decimater dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle hn;
  dec.add(hq);
  dec.add(hn);
  EXPECT_TRUE(dec.initialize());
  return dec.decimate_to_faces(0, faces);
}

struct Call {
  bool binary;
  bool collapse;
  int v0, v1;
};
std::vector<Call> g_calls;

template <typename MeshT>
class RecorderT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(RecorderT, MeshT, Recorder);
  explicit RecorderT(MeshT& mesh) : Base(mesh, true) {}
  float collapse_priority(const CollapseInfo& ci) override {
    g_calls.push_back({true, false, ci.v0.idx(), ci.v1.idx()});
    // Refuses a deterministic share, so refusals at pop time are exercised.
    return (ci.v0.idx() * 7 + ci.v1.idx()) % 5 == 0 ? float(Base::ILLEGAL_COLLAPSE) : float(Base::LEGAL_COLLAPSE);
  }
  void preprocess_collapse(const CollapseInfo& ci) override {
    g_calls.push_back({true, true, ci.v0.idx(), ci.v1.idx()});
  }
};

}  // namespace

TEST(LazyDecimater, OpenMeshsOwnModulesReachTheTargetWithDecimaterTsError) {
  const Mesh original = make_bending_cylinder(24, 48);
  const size_t target = original.n_faces() / 10;
  Mesh a = original, b = original;
  static_decimate<OpenMesh::Decimater::DecimaterT<Mesh>>(a, target);
  static_decimate<Lazy>(b, target);
  EXPECT_EQ(live_faces(a), live_faces(b));
  EXPECT_LE(live_faces(b), target);
  a.garbage_collection();
  b.garbage_collection();
  const double ea = mean_posed_rms(original, a), eb = mean_posed_rms(original, b);
  EXPECT_GT(ea, 0.0);
  EXPECT_LE(eb, 1.05 * ea) << "lazy " << eb << " vs DecimaterT " << ea;
}

TEST(LazyDecimater, SkinnedModulesHoldOutAsWellAsUnderDecimaterTAndNeverFold) {
  const Mesh original = make_bending_cylinder(16, 32);
  Mesh a = original, b = original;
  const auto ra = omsk_test::decimate(a, 0.1);
  const auto rb = omsk_test::decimate<Lazy>(b, 0.1);
  // Within one collapse of each other: a boundary collapse removes one face, others two.
  EXPECT_LE(rb.faces_after, size_t(0.1 * original.n_faces()));
  EXPECT_LE(std::max(ra.faces_after, rb.faces_after) - std::min(ra.faces_after, rb.faces_after), 2u);
  EXPECT_EQ(rb.flipped, 0u) << "verdicts asked right before the collapse cannot be stale";
  EXPECT_EQ(rb.forced, 0u);
  EXPECT_EQ(rb.fallbacks, 0u);
  for (auto vh : b.vertices()) EXPECT_FALSE(b.status(vh).locked()) << "no deferral under the lazy driver";
  omsk_test::expect_valid_skin(b, 4);
  const double ea = held_out_rms(original, a), eb = held_out_rms(original, b);
  EXPECT_LE(eb, 1.05 * ea) << "lazy " << eb << " vs DecimaterT " << ea;
  std::cout << "held-out RMS: DecimaterT " << ea << ", lazy " << eb << "\n";
}

TEST(LazyDecimater, BinaryModulesAreAskedRightBeforeEachCollapseAndTheirRefusalsHold) {
  Mesh mesh = make_bending_cylinder(8, 12);
  Lazy dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  RecorderT<Mesh>::Handle hr;
  dec.add(hq);
  dec.add(hr);
  ASSERT_TRUE(dec.initialize());
  g_calls.clear();
  const size_t n = dec.decimate(40);
  EXPECT_EQ(n, 40u);
  size_t collapses = 0;
  for (size_t i = 0; i < g_calls.size(); ++i) {
    if (!g_calls[i].collapse) continue;
    ++collapses;
    ASSERT_GT(i, 0u);
    const Call& asked = g_calls[i - 1];
    EXPECT_TRUE(!asked.collapse && asked.v0 == g_calls[i].v0 && asked.v1 == g_calls[i].v1)
        << "collapse " << collapses << " was not checked right before it was made";
    EXPECT_NE((asked.v0 * 7 + asked.v1) % 5, 0) << "a refused collapse was made";
  }
  EXPECT_EQ(collapses, n);
  EXPECT_GT(dec.stats().refused, 0u);
}

TEST(LazyDecimater, TheResultDoesNotDependOnTheThreadCount) {
  const Mesh original = make_bending_cylinder(16, 24);
  Mesh meshes[2] = {original, original};
  for (int t = 0; t < 2; ++t) {
    Lazy dec(meshes[t]);
    omsk_test::SkinnedModules<Lazy> modules(dec);
    dec.set_threads(t == 0 ? 1 : 3);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, original.n_faces() / 5);
    EXPECT_GT(dec.stats().collapses, original.n_vertices() / 2);
    meshes[t].garbage_collection();
  }
  omsk_test::expect_same_mesh(meshes[0], meshes[1]);
  const auto h = influences_handle(original);
  for (auto vh : meshes[0].vertices()) EXPECT_EQ(meshes[0].property(h, vh).size(), meshes[1].property(h, vh).size());
}

// The skinned quadric with its one-candidate-per-edge hint switched off: the driver then queues halfedges.
template <typename MeshT>
class HalfedgeQueuedQuadricT : public ModSkinnedQuadricT<MeshT> {
public:
  using Handle = OpenMesh::Decimater::ModHandleT<HalfedgeQueuedQuadricT<MeshT>>;
  explicit HalfedgeQueuedQuadricT(MeshT& mesh) : ModSkinnedQuadricT<MeshT>(mesh) {}
  bool prices_edges() const override { return false; }
};

TEST(LazyDecimater, OneCandidatePerEdgeHalvesThePricingAndChangesNothingElse) {
  const Mesh original = make_bending_cylinder(16, 24);
  Mesh by_edge = original, by_halfedge = original;
  LazyDecimaterStats stats[2];
  for (int run = 0; run < 2; ++run) {
    Mesh& mesh = run == 0 ? by_edge : by_halfedge;
    Lazy dec(mesh);
    ModSkinnedQuadricT<Mesh>::Handle hq;
    HalfedgeQueuedQuadricT<Mesh>::Handle hh;
    ModWeightCapT<Mesh>::Handle hc;
    ModSkinnedFoldOverT<Mesh>::Handle hf;
    if (run == 0)
      dec.add(hq);
    else
      dec.add(hh);
    dec.add(hc);
    dec.add(hf);
    dec.set_threads(1);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, original.n_faces() / 5);
    stats[run] = dec.stats();
    mesh.garbage_collection();
  }
  EXPECT_EQ(stats[0].collapses, stats[1].collapses);
  EXPECT_LT(stats[0].priced, 0.6 * stats[1].priced);
  omsk_test::expect_same_mesh(by_edge, by_halfedge);
}

TEST(LazyDecimater, InitializeNeedsExactlyOnePriorityModuleAndTheMarkIsRemovedAfterwards) {
  Mesh mesh = make_bending_cylinder(8, 8);
  {
    Lazy dec(mesh);
    RecorderT<Mesh>::Handle hr;
    dec.add(hr);
    EXPECT_FALSE(dec.initialize()) << "no priority module";
    EXPECT_EQ(dec.decimate(5), 0u);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
    ModSkinnedQuadricT<Mesh>::Handle hs;
    dec.add(hq);
    dec.add(hs);
    EXPECT_FALSE(dec.initialize()) << "two priority modules";
    dec.remove(hs);
    EXPECT_TRUE(dec.initialize());
    EXPECT_TRUE(checks_at_pop(mesh));
    EXPECT_EQ(dec.decimate(5), 5u);
  }
  EXPECT_FALSE(checks_at_pop(mesh));
}

TEST(LazyDecimater, ACandidateAcceptedAtADearerPlacementIsQueuedAgain) {
  // With the fold check's fallback placements a candidate priced at its solved placement may be accepted
  // at a dearer one: the driver asks the priority module again and queues it behind cheaper candidates.
  // Without them the price cannot change at the checks, and nothing is queued again.
  for (bool fallback : {false, true}) {
    Mesh mesh = omsk_test::load_character("X/Testwuson.X", 8);
    Lazy dec(mesh);
    omsk_test::SkinnedModules<Lazy> m(dec);
    dec.module(m.fold).set_max_angle(20.0);
    dec.module(m.fold).set_fallback_placement(fallback);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, mesh.n_faces() / 100);
    const size_t fold_fallbacks = dec.module(m.quadric).solver().stats().fold_fallbacks;
    if (fallback) {
      EXPECT_GT(dec.stats().requeued, 0u);
      EXPECT_GT(fold_fallbacks, 0u);
    } else {
      EXPECT_EQ(dec.stats().requeued, 0u);
      EXPECT_EQ(fold_fallbacks, 0u);
    }
  }
}

TEST(LazyDecimater, TheTopologyStopsCollapsesAtATetrahedronAndATriangle) {
  Mesh mesh = make_bending_cylinder(8, 8);
  Lazy dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  ASSERT_TRUE(dec.initialize());
  EXPECT_TRUE(dec.topology_allows_a_collapse());
  Mesh tiny;
  tiny.request_vertex_status();
  tiny.request_edge_status();
  tiny.request_face_status();
  std::vector<Mesh::VertexHandle> v;
  for (auto p : {Mesh::Point(0, 0, 0), Mesh::Point(1, 0, 0), Mesh::Point(0, 1, 0), Mesh::Point(0, 0, 1)})
    v.push_back(tiny.add_vertex(p));
  for (auto f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})
    tiny.add_face(v[f[0]], v[f[1]], v[f[2]]);
  auto t = tiny.add_vertex(Mesh::Point(5, 0, 0)), u = tiny.add_vertex(Mesh::Point(6, 0, 0)),
       w = tiny.add_vertex(Mesh::Point(5, 1, 0));
  tiny.add_face(t, u, w);
  Lazy stuck(tiny);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle hq2;
  stuck.add(hq2);
  ASSERT_TRUE(stuck.initialize());
  EXPECT_FALSE(stuck.topology_allows_a_collapse()) << "a tetrahedron and a lone triangle are as small as they get";
  EXPECT_EQ(stuck.decimate(0), 0u);
}
