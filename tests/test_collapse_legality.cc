// CollapseLegality: the same answers as OpenMesh's TriConnectivity::is_collapse_ok and
// BaseDecimaterT::is_collapse_legal, on every halfedge, all the way down a decimation.
#include "helpers.hh"

#include <OpenMeshSkinned/Collapse/CollapseLegality.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>

#include <array>
#include <random>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// OpenMesh's own is_collapse_legal, which the base class keeps protected.
struct LibraryLegality : OpenMesh::Decimater::BaseDecimaterT<Mesh> {
  explicit LibraryLegality(Mesh& mesh) : BaseDecimaterT(mesh) {}
  using BaseDecimaterT::is_collapse_legal;
};

// Compares both tests on every halfedge; returns how many halfedges the library called legal.
size_t expect_same_answers(Mesh& mesh, LibraryLegality& library, const std::string& where) {
  size_t legal = 0, differences = 0;
  for (auto h : mesh.halfedges()) {
    const bool ok = mesh.is_collapse_ok(h);
    const bool ours_ok = link_condition_ok(mesh, h);
    bool lib_legal = false, ours_legal = false;
    if (!mesh.status(mesh.edge_handle(h)).deleted()) {
      const OpenMesh::Decimater::CollapseInfoT<Mesh> ci(mesh, h);
      lib_legal = library.is_collapse_legal(ci);
      ours_legal = collapse_legal(mesh, ci);
    }
    if (ok != ours_ok || lib_legal != ours_legal) {
      if (++differences <= 3)
        ADD_FAILURE() << where << ": halfedge " << h.idx() << " is_collapse_ok " << ok << " ours " << ours_ok
                      << ", is_collapse_legal " << lib_legal << " ours " << ours_legal;
    }
    legal += lib_legal;
  }
  EXPECT_EQ(differences, 0u) << where;
  return legal;
}

// Random legal collapses until none is left, comparing every answer every few collapses; some vertices
// are locked and some edges are features, so every branch of the test is taken.
void decimate_comparing(Mesh mesh, const std::string& name, unsigned seed, size_t at_least) {
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  std::mt19937 rng(seed);
  for (auto v : mesh.vertices()) {
    if (rng() % 50 == 0) mesh.status(v).set_locked(true);
    if (rng() % 40 == 0) mesh.status(v).set_feature(true);
  }
  for (auto e : mesh.edges())
    if (rng() % 30 == 0) mesh.status(e).set_feature(true);
  LibraryLegality library(mesh);
  size_t collapses = 0;
  const size_t every = std::max<size_t>(1, mesh.n_faces() / 400);
  for (;;) {
    if (collapses % every == 0 &&
        expect_same_answers(mesh, library, name + " after " + std::to_string(collapses) + " collapses") == 0)
      break;
    if (::testing::Test::HasFailure()) return;
    // A random legal halfedge: random tries first, then the first legal one in a full scan.
    auto legal = [&](Mesh::HalfedgeHandle h) {
      return !mesh.status(mesh.edge_handle(h)).deleted() &&
             library.is_collapse_legal(OpenMesh::Decimater::CollapseInfoT<Mesh>(mesh, h));
    };
    Mesh::HalfedgeHandle pick;
    for (int tries = 0; tries < 64 && !pick.is_valid(); ++tries) {
      const Mesh::HalfedgeHandle h(int(rng() % mesh.n_halfedges()));
      if (legal(h)) pick = h;
    }
    for (auto h : mesh.halfedges())
      if (!pick.is_valid() && legal(h)) pick = h;
    if (!pick.is_valid()) {
      expect_same_answers(mesh, library, name + " at the end");
      break;
    }
    mesh.collapse(pick);
    ++collapses;
  }
  EXPECT_GE(collapses, at_least) << name;
}

}  // namespace

TEST(CollapseLegality, AnswersAsOpenMeshOnAClosedCharacterWithManyPieces) {
  decimate_comparing(omsk_test::load_character("X/Testwuson.X", 1), "Testwuson", 1, 1500);
}

TEST(CollapseLegality, AnswersAsOpenMeshOnOpenTubesAndBoundaries) {
  decimate_comparing(make_bending_cylinder(12, 10), "open cylinder", 2, 100);
  decimate_comparing(omsk_test::load_character("glTF2/simple_skin/simple_skin.gltf", 1), "simple_skin", 3, 4);
  decimate_comparing(omsk_test::grid_with_uv_seam(), "grid", 4, 4);
}

TEST(CollapseLegality, ATetrahedronAndALoneTriangleAreFinal) {
  Mesh tiny;
  tiny.request_vertex_status();
  tiny.request_edge_status();
  tiny.request_face_status();
  std::vector<Mesh::VertexHandle> v;
  for (auto p : {Mesh::Point(0, 0, 0), Mesh::Point(1, 0, 0), Mesh::Point(0, 1, 0), Mesh::Point(0, 0, 1),
                 Mesh::Point(5, 0, 0), Mesh::Point(6, 0, 0), Mesh::Point(5, 1, 0)})
    v.push_back(tiny.add_vertex(p));
  for (auto f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {4, 5, 6}})
    tiny.add_face(v[f[0]], v[f[1]], v[f[2]]);
  LibraryLegality library(tiny);
  EXPECT_EQ(expect_same_answers(tiny, library, "tetrahedron"), 0u);
  for (auto h : tiny.halfedges()) EXPECT_FALSE(collapse_legal(tiny, OpenMesh::Decimater::CollapseInfoT<Mesh>(tiny, h)));
}
