// skinned-decimate on meshes animated without a skeleton: MD2 files and numbered OBJ sequences, key
// frames, pose selection and the segmentation mode, as a technical artist runs them.
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <tiny_gltf.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace fs = std::filesystem;

namespace {

omsk_test::CommandResult cli(const std::string& args, const fs::path& cwd) {
  return omsk_test::run_command(OMSK_CLI_EXE, args, cwd);
}
fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("cli_frames", name); }
const std::string faerie = std::string("'") + OMSK_TEST_MODELS + "/MD2/faerie.md2'";

tinygltf::Model load(const fs::path& p) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, p.string())) << err;
  return m;
}

// Morph targets of the first primitive and whether an animation drives the node's weights.
std::pair<size_t, bool> targets_and_weight_animation(const tinygltf::Model& m) {
  bool weights = false;
  for (const auto& a : m.animations)
    for (const auto& c : a.channels) weights |= c.target_path == "weights";
  return {m.meshes.at(0).primitives.at(0).targets.size(), weights};
}

// An 8 x 8 grid of squares whose far half folds up by \p angle degrees about the line x = 4.
void write_folding_grid(const fs::path& p, double angle) {
  std::ofstream f(p);
  const double a = angle * M_PI / 180.0;
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      const double x = i <= 4 ? i : 4 + (i - 4) * std::cos(a), z = i <= 4 ? 0 : (i - 4) * std::sin(a);
      f << "v " << x << " " << j << " " << z << "\n";
    }
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const int v = j * 9 + i + 1;
      f << "f " << v << " " << v + 1 << " " << v + 10 << "\nf " << v << " " << v + 10 << " " << v + 9 << "\n";
    }
}

}  // namespace

TEST(CliFrames, AnMd2BecomesLodsThatPlayItsAnimation) {
  const auto d = scratch("md2");
  const auto r = cli(faerie + " -o f.glb --lods 0.5,0.25 --report f.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("read 198 frames as one clip"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames, 198 frames, 654 triangles in"), std::string::npos) << r.out;
  for (const char* f : {"f_lod1.glb", "f_lod2.glb"}) {
    omsk_test::expect_valid_gltf((d / f).string());
    const auto [targets, animated] = targets_and_weight_animation(load(d / f));
    EXPECT_EQ(targets, 197u);
    EXPECT_TRUE(animated);
  }
  nlohmann::json rep = omsk_test::read_json(d / "f.json");
  EXPECT_EQ(rep["method"], "frames");
  for (const auto& l : rep["lods"]) {
    EXPECT_GT(l["heldout_rms"].get<double>(), 0.0);
    EXPECT_LT(l["heldout_rms"].get<double>(), 2.0);
  }
}

TEST(CliFrames, LightSimplificationKeepsTheOutlineOfSheetsFoldedBackOnThemselves) {
  // faerie's wings and flaps are two layers folded at their outline: without the fold's planes the first
  // collapse (of 11) cut a flap's tip, 1.4% of the diagonal in held-out frames; the fold's planes keep it.
  const auto d = scratch("md2light");
  const auto r = cli(faerie + " -o l.glb --faces 632 --report l.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "l.json");
  const auto& l = rep["lods"][0];
  EXPECT_EQ(l["faces"].get<size_t>(), 632u);
  EXPECT_LT(l["heldout_hausdorff"].get<double>(), 0.8);  // 0.46 measured
  EXPECT_LT(l["heldout_rms"].get<double>(), 0.02);       // 0.010 measured
}

TEST(CliFrames, KeyframesKeepThatManyFramesChosenByTheGa) {
  const auto d = scratch("keys");
  const auto r = cli(faerie + " -o k.glb --ratio 0.5 --keyframes 30", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("key frames (GA"), std::string::npos) << r.out;
  omsk_test::expect_valid_gltf((d / "k.glb").string());
  EXPECT_EQ(targets_and_weight_animation(load(d / "k.glb")).first, 29u);
  // On a skinned character it is a usage error, and nothing is written.
  const auto s = cli(std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' -o w.glb --keyframes 5", d);
  EXPECT_EQ(s.code, 2) << s.out;
  EXPECT_NE(s.out.find("--keyframes"), std::string::npos);
  EXPECT_FALSE(fs::exists(d / "w.glb"));
}

TEST(CliFrames, SegmentWritesColouredPartsAndTheirFaces) {
  const auto d = scratch("segment");
  const auto r = cli(std::string("'") + OMSK_TEST_MODELS + "/MD2/sydney.md2' --segment s.glb", d);
  ASSERT_EQ(r.code, 0) << r.out;
  omsk_test::expect_valid_gltf((d / "s.glb").string());
  nlohmann::json j = omsk_test::read_json(d / "s.json");
  EXPECT_GT(j["parts"].get<int>(), 4);
  EXPECT_EQ(j["face_part"].size(), 679u);
  const auto m = load(d / "s.glb");
  EXPECT_EQ(m.materials.size(), j["parts"].get<size_t>());
  EXPECT_FALSE(fs::exists(d / "s_lod1.glb"));
  // A mesh that does not move cannot be segmented by its motion.
  const auto still = cli(std::string("'") + OMSK_TEST_MODELS + "/OBJ/box.obj' --segment b.glb", d);
  EXPECT_EQ(still.code, 2) << still.out;
  EXPECT_FALSE(fs::exists(d / "b.glb"));
}

TEST(CliFrames, ANumberedObjSequenceIsOneAnimation) {
  const auto d = scratch("sequence");
  for (int f = 1; f <= 9; ++f) write_folding_grid(d / ("fold_000" + std::to_string(f) + ".obj"), 10.0 * (f - 1));
  const auto r = cli("fold_0001.obj -o fold.glb --ratio 0.3 --poses 3", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("one frame of 9 files fold_0001.obj .. fold_0009.obj"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("9 frames"), std::string::npos) << r.out;
  omsk_test::expect_valid_gltf((d / "fold.glb").string());
  EXPECT_EQ(targets_and_weight_animation(load(d / "fold.glb")).first, 8u);
  // The inputs are untouched, and --no-sequence reads the file alone (no animation).
  const auto alone = cli("fold_0005.obj -o one.glb --ratio 0.5 --no-sequence", d);
  ASSERT_EQ(alone.code, 0) << alone.out;
  EXPECT_NE(alone.out.find("rest pose only"), std::string::npos) << alone.out;
  // Formats that carry a character are never taken for frames: two numbered copies are two versions.
  fs::copy_file(fs::path(OMSK_TEST_MODELS) / "X/Testwuson.X", d / "hero_1.x");
  fs::copy_file(fs::path(OMSK_TEST_MODELS) / "X/Testwuson.X", d / "hero_2.x");
  const auto hero = cli("hero_2.x -o hero.glb --ratio 0.5 --no-eval", d);
  ASSERT_EQ(hero.code, 0) << hero.out;
  EXPECT_EQ(hero.out.find("one frame of"), std::string::npos) << hero.out;
  EXPECT_NE(hero.out.find("skinned"), std::string::npos) << hero.out;
  // A frame with other faces: one line naming it, exit 1, nothing written.
  std::ofstream(d / "fold_0010.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const auto bad = cli("fold_0001.obj -o bad.glb", d);
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_NE(bad.out.find("fold_0010.obj: not the same mesh"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(d / "bad.glb"));
}

TEST(CliFrames, PoseSelectGaSaysSoAndStillJudgesOnHeldOutFrames) {
  const auto d = scratch("ga");
  const auto r = cli(faerie + " -o g.glb --ratio 0.5 --pose-select ga --poses 6 --report g.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("chosen by the key-frame GA"), std::string::npos) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "g.json");
  // No held-out frame is an example.
  const auto& l = rep["lods"][0];
  std::set<double> examples;
  for (const auto& e : l["example_pose_times"]) examples.insert(e["time"].get<double>());
  for (const auto& h : l["heldout_times"]) EXPECT_EQ(examples.count(h["time"].get<double>()), 0u);
  EXPECT_GE(examples.size(), 6u);
}

TEST(CliFrames, TheFrameMethodsHonourTheInfluenceCapOnSkinnedCharacters) {
  const auto d = scratch("cap");
  for (const char* method : {"frames", "deform"}) {
    const auto r = cli(std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' -o w.glb --lods 0.5,0.25 --method " +
                           method + " --max-influences 2 --report w.json --no-eval --quiet",
                       d);
    ASSERT_EQ(r.code, 0) << r.out;
    nlohmann::json rep = omsk_test::read_json(d / "w.json");
    for (const auto& l : rep["lods"]) EXPECT_LE(l["max_influences"].get<int>(), 2) << method;
  }
}
