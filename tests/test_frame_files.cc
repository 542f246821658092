// Which files make one mesh animated without a skeleton (the rule the CLI and the Python package share).
#include "helpers.hh"

#include <OpenMeshSkinned/IO/FrameFiles.hh>

#include <filesystem>
#include <fstream>

using namespace OpenMeshSkinned;
using omsk_test::model;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void touch(const fs::path& p) { std::ofstream(p) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"; }

}  // namespace

TEST(FrameFiles, AFileThatStoresFramesIsItsOwnAnimation) {
  EXPECT_EQ(frame_files(model("MD2/faerie.md2")), std::vector<std::string>{model("MD2/faerie.md2")});
  EXPECT_TRUE(frame_files(model("X/Testwuson.X")).empty());
}

TEST(FrameFiles, NumberedStillMeshesAreOneAnimationUnlessAskedNot) {
  const fs::path d = fresh_dir("frame_files");
  for (const char* n : {"walk_1.obj", "walk_2.OBJ", "walk_3.obj", "hero_1.glb", "hero_2.glb", "lone_1.ply"})
    touch(d / n);
  EXPECT_EQ(frame_files((d / "walk_3.obj").string()).size(), 2u);  // walk_2.OBJ is another extension
  EXPECT_TRUE(frame_files((d / "walk_3.obj").string(), false).empty());
  // Two versions of a character are not frames, and one numbered file is just a mesh.
  EXPECT_TRUE(frame_files((d / "hero_1.glb").string()).empty());
  EXPECT_TRUE(frame_files((d / "lone_1.ply").string()).empty());
}

TEST(FrameFiles, QuakeFramesPlayAtTenHertzSequencesAtTwentyFour) {
  EXPECT_EQ(frame_rate({"a.md2"}, 0.0), 10.0);
  EXPECT_EQ(frame_rate({"a_1.obj", "a_2.obj"}, 0.0), 24.0);
  EXPECT_EQ(frame_rate({"a.md2"}, 30.0), 30.0);
}
