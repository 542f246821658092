// Vertex-animated files (Quake MD2) and numbered mesh sequences read as frame animations.
#include "helpers.hh"

#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>

#include <filesystem>
#include <fstream>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using omsk_test::model;
namespace fs = std::filesystem;

namespace {

// A unit square of two triangles whose corner 2 is lifted by \p lift; \p extra adds a stray triangle.
void write_obj(const fs::path& p, double lift, bool extra = false) {
  std::ofstream f(p);
  f << "v 0 0 0\nv 1 0 0\nv 1 1 " << lift << "\nv 0 1 0\n";
  if (extra) f << "v 2 2 0\n";
  f << "f 1 2 3\nf 1 3 4\n";
  if (extra) f << "f 2 5 3\n";
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(ImportFrames, Md2HeadersGiveTheirFrameCounts) {
  EXPECT_EQ(stored_frame_count(model("MD2/faerie.md2")), 198u);
  EXPECT_EQ(stored_frame_count(model("MD2/sydney.md2")), 198u);
  EXPECT_EQ(stored_frame_count(model("MDL/MDL3 (3DGS A4)/minigun.MDL")), 8u);  // 3D GameStudio: Quake's MDL header
  EXPECT_EQ(stored_frame_count(model("MDL/MDL7 (3DGS A7)/PhosphoricAcid_MDl7.mdl")), 1u);
  EXPECT_EQ(stored_frame_count(model("OBJ/box.obj")), 1u);
}

TEST(ImportFrames, StoredFramesThatAllHaveOneShapeAreAStillMeshAndSaySo) {
  // The 3D GameStudio minigun stores 8 frames, and assimp gives the same positions for each.
  Mesh mesh;
  const auto rep = import_frame_animation({model("MDL/MDL3 (3DGS A4)/minigun.MDL")}, mesh, {}, 10.0);
  EXPECT_TRUE(frame_times(mesh).empty());
  EXPECT_TRUE(morph_targets(mesh).empty());
  EXPECT_TRUE(clips(mesh).empty());
  EXPECT_EQ(mesh.n_faces(), 576u);
  bool said = false;
  for (const auto& w : rep.warnings) said |= w.find("8 stored frames, all with the same shape") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(ImportFrames, EveryStoredFrameOfAnMd2BecomesAFrame) {
  Mesh mesh;
  const auto rep = import_frame_animation({model("MD2/faerie.md2")}, mesh, {}, 10.0);
  ASSERT_EQ(frame_times(mesh).size(), 198u);
  EXPECT_DOUBLE_EQ(frame_times(mesh)[10], 1.0);
  EXPECT_EQ(rep.morph_targets, 197u);
  EXPECT_EQ(clips(mesh).size(), 1u);
  // Frame 57 is what assimp reads when asked for frame 57 alone (which welds two pairs of vertices that
  // touch in that frame: 382 against 384), and it differs from frame 0.
  ImportOptions o;
  o.frame = 57;
  Mesh alone;
  import_skinned(model("MD2/faerie.md2"), alone, o);
  const FramePositions f57 = frame_positions(mesh, 57), f0 = frame_positions(mesh, 0);
  double moved = 0.0, worst = 0.0;
  for (auto v : mesh.vertices()) {
    double nearest = HUGE_VAL;
    for (auto a : alone.vertices()) nearest = std::min(nearest, (f57[v.idx()] - to_eigen(alone.point(a))).norm());
    worst = std::max(worst, nearest);
    moved = std::max(moved, (f57[v.idx()] - f0[v.idx()]).norm());
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(moved, 1.0);
}

TEST(ImportFrames, ANumberedSequenceIsReadInNumberOrder) {
  const fs::path d = fresh_dir("seq");
  for (int i : {1, 2, 10}) write_obj(d / ("walk_" + std::to_string(i) + ".obj"), 0.1 * i);
  write_obj(d / "other_1.obj", 5.0);
  const auto files = numbered_sequence((d / "walk_2.obj").string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(fs::path(files[2]).filename(), "walk_10.obj");
  Mesh mesh;
  import_frame_animation(files, mesh, {}, 24.0);
  ASSERT_EQ(frame_times(mesh).size(), 3u);
  double lift[3];
  for (size_t f = 0; f < 3; ++f) {
    lift[f] = 0.0;
    for (const auto& p : frame_positions(mesh, f)) lift[f] = std::max(lift[f], p.z());
  }
  EXPECT_NEAR(lift[0], 0.1, 1e-6);
  EXPECT_NEAR(lift[1], 0.2, 1e-6);
  EXPECT_NEAR(lift[2], 1.0, 1e-6);
  EXPECT_EQ(numbered_sequence((d / "plain.obj").string()), std::vector<std::string>{(d / "plain.obj").string()});
}

TEST(ImportFrames, AFrameWithOtherFacesIsRefusedByName) {
  const fs::path d = fresh_dir("bad_seq");
  write_obj(d / "f_1.obj", 0.0);
  write_obj(d / "f_2.obj", 0.5, true);
  Mesh mesh;
  try {
    import_frame_animation(numbered_sequence((d / "f_1.obj").string()), mesh, {}, 24.0);
    FAIL() << "accepted a frame with other faces";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("f_2.obj: not the same mesh"), std::string::npos) << e.what();
  }
  EXPECT_THROW(import_frame_animation({model("OBJ/box.obj")}, mesh, {}, 24.0), IOError);
}
