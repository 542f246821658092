// The deferral of stale verdicts (Solver/StaleVerdictsT.hh), driven by hand as DecimaterT would.
#include "helpers.hh"

#include <OpenMeshSkinned/Solver/StaleVerdictsT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using CI = OpenMesh::Decimater::CollapseInfoT<Mesh>;

namespace {

// A 5x5 vertex grid.
Mesh grid(std::vector<Mesh::VertexHandle>& v) {
  Mesh mesh;
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k) v.push_back(mesh.add_vertex(Mesh::Point(k, i, 0)));
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const auto a = v[i * 5 + k], b = v[i * 5 + k + 1], c = v[(i + 1) * 5 + k], d = v[(i + 1) * 5 + k + 1];
      mesh.add_face(a, b, d);
      mesh.add_face(a, d, c);
    }
  return mesh;
}

}  // namespace

TEST(StaleVerdicts, TheCheapestLegalCollapseOfASweepIsRemembered) {
  std::vector<Mesh::VertexHandle> v;
  Mesh mesh = grid(v);
  StaleVerdictsT<Mesh> sv(mesh);
  sv.prepare();
  const auto z = v[12];
  std::vector<Mesh::HalfedgeHandle> out;
  for (auto h : mesh.voh_range(z)) out.push_back(h);
  sv.begin_pricing(CI(mesh, out[0]));
  EXPECT_FALSE(sv.has_legal(z));
  sv.note_legal(CI(mesh, out[0]), 2.0);
  sv.note_legal(CI(mesh, out[1]), 1.0);
  sv.note_legal(CI(mesh, out[2]), 1.0 + 1e-12);  // equal in float: the first one stays, as in DecimaterT
  EXPECT_TRUE(sv.has_legal(z));
  EXPECT_DOUBLE_EQ(sv.best_error(), 1.0);
  // A new sweep of the same vertex (after a collapse elsewhere) starts afresh.
  sv.begin_collapse(CI(mesh, mesh.halfedge_handle(v[0])));
  sv.begin_pricing(CI(mesh, out[0]));
  EXPECT_FALSE(sv.has_legal(z));
}

TEST(StaleVerdicts, AStoredCollapseThatNowFoldsIsLockedUntilReleased) {
  std::vector<Mesh::VertexHandle> v;
  Mesh mesh = grid(v);
  StaleVerdictsT<Mesh> sv(mesh);
  sv.prepare();
  // z = (2,2) stores its collapse towards (3,2); the user locked (1,2).
  const auto z = v[12], user = v[11];
  mesh.status(user).set_locked(true);
  const auto zh = mesh.find_halfedge(z, v[13]);
  sv.begin_pricing(CI(mesh, zh));
  sv.note_legal(CI(mesh, zh), 1.0);
  sv.begin_pricing(CI(mesh, mesh.find_halfedge(user, z)));
  sv.note_legal(CI(mesh, mesh.find_halfedge(user, z)), 1.0);
  // A collapse elsewhere whose survivor v1 = (2,3) neighbours z; v0 = (2,4) on the border.
  const auto h = mesh.find_halfedge(v[22], v[17]);
  sv.begin_collapse(CI(mesh, h));
  mesh.collapse(h);
  int asked = 0;
  const size_t locked = sv.defer_around(v[17], [&](const CI& ci) {
    ++asked;
    return ci.v0 == z;  // only z's stored collapse folds now
  });
  EXPECT_EQ(locked, 1u);
  EXPECT_GE(asked, 1);
  EXPECT_TRUE(mesh.status(z).locked());
  EXPECT_TRUE(mesh.status(user).locked());
  sv.release();
  EXPECT_FALSE(mesh.status(z).locked());
  EXPECT_TRUE(mesh.status(user).locked()) << "a vertex the user locked is never unlocked";
  release_stale_marks(mesh);
  OpenMesh::VPropHandleT<bool> d;
  EXPECT_FALSE(mesh.get_property_handle(d, kDeferredProperty));
}
