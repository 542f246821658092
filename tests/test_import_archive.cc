// ImportArchive: what the isolated reader sends back is the import, exactly.
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportArchive.hh>
#include <OpenMeshSkinned/Skin/Morph.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace OpenMeshSkinned;

namespace {
std::string model(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }

// Where the halfedges' next handles start in \p mesh's archive. The layout: magic and version, then each array
// as a 64-bit length and its elements: points (3 doubles per vertex), the vertices' halfedges, the halfedges'
// vertices, then their next halfedges.
size_t next_offset(const SkinnedMesh& mesh) {
  const size_t nv = mesh.n_vertices(), nh = mesh.n_halfedges();
  return 8 + (8 + 24 * nv) + (8 + 4 * nv) + (8 + 4 * nh) + 8;
}
}  // namespace

class ArchiveRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(ArchiveRoundTrip, RebuildsTheSameCharacter) {
  SkinnedMesh a;
  const ImportReport ra = import_skinned(model(GetParam()), a);
  const std::string bytes = save_import(a, ra);
  SkinnedMesh b;
  ImportReport rb;
  load_import(bytes, b, rb);
  ASSERT_EQ(b.n_vertices(), a.n_vertices());
  ASSERT_EQ(b.n_faces(), a.n_faces());
  for (auto vh : a.vertices()) {
    ASSERT_EQ(b.point(vh), a.point(vh));
    ASSERT_EQ(b.property(influences_handle(b), vh), a.property(influences_handle(a), vh));
  }
  EXPECT_EQ(skeleton(b).size(), skeleton(a).size());
  EXPECT_EQ(clips(b).size(), clips(a).size());
  EXPECT_EQ(materials(b).size(), materials(a).size());
  EXPECT_EQ(morph_targets(b).size(), morph_targets(a).size());
  EXPECT_EQ(rb.warnings, ra.warnings);
  EXPECT_EQ(rb.faces, ra.faces);
  // The same connectivity, handle for handle: what is decimated in the parent is what the reader made.
  ASSERT_EQ(b.n_halfedges(), a.n_halfedges());
  for (auto vh : a.vertices()) ASSERT_EQ(b.halfedge_handle(vh), a.halfedge_handle(vh));
  for (auto fh : a.faces()) ASSERT_EQ(b.halfedge_handle(fh), a.halfedge_handle(fh));
  for (auto heh : a.halfedges()) {
    ASSERT_EQ(b.to_vertex_handle(heh), a.to_vertex_handle(heh));
    ASSERT_EQ(b.next_halfedge_handle(heh), a.next_halfedge_handle(heh));
    ASSERT_EQ(b.face_handle(heh), a.face_handle(heh));
    if (a.is_boundary(heh)) {  // no face's corner: its attributes were never set, and arrive as zeros
      ASSERT_EQ(b.normal(heh), SkinnedMesh::Normal(0, 0, 0));
      continue;
    }
    ASSERT_EQ(b.normal(heh), a.normal(heh));
    ASSERT_EQ(b.texcoord2D(heh), a.texcoord2D(heh));
  }
  // Corners, properties and report in the same order: saving again gives the same bytes.
  EXPECT_EQ(save_import(b, rb), bytes);
}

INSTANTIATE_TEST_SUITE_P(RealAssets, ArchiveRoundTrip,
                         ::testing::Values("X/Testwuson.X",
                                           "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
                                           "glTF2/BoxTextured-glTF/BoxTextured.gltf",
                                           "FBX/animation_with_skeleton.fbx"));

TEST(ImportArchive, RefusesBytesThatAreNotOne) {
  SkinnedMesh m;
  ImportReport r;
  EXPECT_THROW(load_import("", m, r), IOError);
  EXPECT_THROW(load_import(std::string(100, 'x'), m, r), IOError);
  SkinnedMesh a;
  const std::string bytes = save_import(
      a =
          [] {
            SkinnedMesh t;
            import_skinned(model("X/Testwuson.X"), t);
            return t;
          }(),
      ImportReport{});
  EXPECT_THROW(load_import(bytes.substr(0, bytes.size() / 2), m, r), IOError);
}

// The connectivity is taken as sent, so a handle that does not fit is refused before the mesh is built: a
// crash or an endless walk around a vertex later would not name the archive.
TEST(ImportArchive, RefusesConnectivityThatDoesNotFit) {
  SkinnedMesh a;
  import_skinned(model("X/Testwuson.X"), a);
  const std::string good = save_import(a, ImportReport{});
  const size_t nh = a.n_halfedges(), next_at = next_offset(a);
  auto with_next = [&](int32_t next_of_first) {
    std::string bytes = good;
    std::memcpy(&bytes[next_at], &next_of_first, 4);
    return bytes;
  };
  SkinnedMesh m;
  ImportReport r;
  ASSERT_EQ(a.next_halfedge_handle(SkinnedMesh::HalfedgeHandle(0)).idx(), [&] {
    int32_t n = 0;
    std::memcpy(&n, &good[next_at], 4);
    return n;
  }()) << "the layout above is out of date";
  EXPECT_NO_THROW(load_import(with_next(a.next_halfedge_handle(SkinnedMesh::HalfedgeHandle(0)).idx()), m, r));
  EXPECT_THROW(load_import(with_next(int32_t(nh)), m, r), IOError);  // out of range
  EXPECT_THROW(load_import(with_next(0), m, r), IOError);            // its own next: leaves another vertex
  EXPECT_THROW(load_import(with_next(-1), m, r), IOError);
}

// Where two fans meet at a vertex, a border halfedge reaching it could be given the other fan's way out: every
// other check still holds, and only the permutation check sees that one way out is now nobody's next.
TEST(ImportArchive, RefusesTwoHalfedgesWithTheSameNext) {
  SkinnedMesh a;
  request_skinned_attributes(a);
  const auto h_inf = add_skin(a);
  const auto c = a.add_vertex({0, 0, 0});
  const auto a0 = a.add_vertex({1, 0, 0}), a1 = a.add_vertex({1, 1, 0});
  const auto b0 = a.add_vertex({-1, 0, 0}), b1 = a.add_vertex({-1, -1, 0});
  for (auto vh : a.vertices()) a.property(h_inf, vh) = Influences::rigid(0);
  ASSERT_TRUE(a.add_face(c, a0, a1).is_valid() && a.add_face(c, b0, b1).is_valid());
  clear_corner_attributes(a);
  std::vector<int32_t> into_c;  // the border halfedges reaching the centre, one per fan
  for (auto heh : a.halfedges())
    if (a.is_boundary(heh) && a.to_vertex_handle(heh) == c) into_c.push_back(heh.idx());
  ASSERT_EQ(into_c.size(), 2u);
  const std::string good = save_import(a, ImportReport{});
  const size_t next_at = next_offset(a);
  int32_t sent = -1;
  std::memcpy(&sent, &good[next_at + 4 * size_t(into_c[0])], 4);
  ASSERT_EQ(sent, a.next_halfedge_handle(SkinnedMesh::HalfedgeHandle(into_c[0])).idx()) << "layout out of date";
  std::string bad = good;
  const int32_t other_way_out = a.next_halfedge_handle(SkinnedMesh::HalfedgeHandle(into_c[1])).idx();
  std::memcpy(&bad[next_at + 4 * size_t(into_c[0])], &other_way_out, 4);
  SkinnedMesh m;
  ImportReport r;
  EXPECT_NO_THROW(load_import(good, m, r));
  EXPECT_THROW(load_import(bad, m, r), IOError);
}
