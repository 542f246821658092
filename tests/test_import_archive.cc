// ImportArchive: what the isolated reader sends back is the import, exactly.
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportArchive.hh>
#include <OpenMeshSkinned/Skin/Morph.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

#include <string>

using namespace OpenMeshSkinned;

namespace {
std::string model(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }
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
