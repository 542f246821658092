// The job as a library call: what make_lods() gives a C++ caller, and that the CLI is only a shell around it.
#include "helpers.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Lod/MakeLods.hh>
#include <OpenMeshSkinned/Lod/SaveLods.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace OpenMeshSkinned;
namespace fs = std::filesystem;

namespace {

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

LodOptions quick(std::vector<double> ratios) {
  LodOptions o;
  o.ratios = std::move(ratios);
  o.poses = 2;
  return o;
}

}  // namespace

TEST(MakeLods, ChainLargestFirstWithReports) {
  const SkinnedMesh leg = make_bending_cylinder(16, 32);
  const size_t faces_before = leg.n_faces();
  const LodChain chain = make_lods(leg, quick({0.25, 0.5}));
  EXPECT_EQ(leg.n_faces(), faces_before) << "the input is not changed";
  EXPECT_EQ(chain.method, "skinned");
  ASSERT_EQ(chain.levels.size(), 2u);
  EXPECT_DOUBLE_EQ(chain.levels[0].report.ratio, 0.5);
  EXPECT_DOUBLE_EQ(chain.levels[1].report.ratio, 0.25);
  for (const auto& [report, mesh] : chain.levels) {
    EXPECT_EQ(report.faces, mesh.n_faces());
    EXPECT_EQ(report.vertices, mesh.n_vertices());
    EXPECT_LE(report.faces, report.target);
    EXPECT_TRUE(report.evaluated);
    EXPECT_GT(report.rms, 0.0);
    EXPECT_GE(report.hausdorff, report.rms);
    EXPECT_LE(report.max_influences, 4);
    EXPECT_EQ(report.joints, skeleton(leg).size());
  }
  EXPECT_LT(chain.levels[0].report.rms, chain.levels[1].report.rms);
  EXPECT_EQ(chain.poses.examples.size(), 3u) << "two example poses and the bind pose";
  EXPECT_FALSE(chain.poses.heldout.empty());
}

TEST(MakeLods, FacesAskedForAndEvaluatedAlone) {
  const SkinnedMesh leg = make_bending_cylinder(16, 32);
  LodOptions o = quick({});
  o.faces = {200};
  const LodChain chain = make_lods(leg, o);
  ASSERT_EQ(chain.levels.size(), 1u);
  EXPECT_EQ(chain.levels[0].report.target, 200u);
  EXPECT_LE(chain.levels[0].mesh.n_faces(), 200u);
  // evaluate() on its own gives the chain's numbers for the chain's frames.
  const HeldOutError e = evaluate(leg, chain.levels[0].mesh, chain.poses.heldout);
  EXPECT_NEAR(e.rms, chain.levels[0].report.rms, 1e-12);
  EXPECT_NEAR(e.hausdorff, chain.levels[0].report.hausdorff, 1e-12);
  EXPECT_NEAR(evaluate(leg, leg, chain.poses.heldout).rms, 0.0, 1e-9);
}

TEST(MakeLods, RefusesWithTheCommandLinesMessages) {
  const SkinnedMesh leg = make_bending_cylinder(8, 8);
  auto message = [&](const LodOptions& o) {
    try {
      make_lods(leg, o);
    } catch (const LodOptionsError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(quick({1.5})), "--lods: every ratio must be in (0, 1], got 1.5000");
  LodOptions o = quick({0.5});
  o.faces = {100000};
  EXPECT_EQ(message(o), "--faces 100000 is more than the input's " + std::to_string(leg.n_faces()) + " triangles");
  o = quick({0.5});
  o.max_influences = 9;
  EXPECT_EQ(message(o), "--max-influences must be 1 to 8");
  o = quick({0.5});
  o.method = "best";
  EXPECT_EQ(message(o).rfind("--method must be skinned, ", 0), 0u);
  o = quick({0.5});
  o.pose_select = "best";
  EXPECT_EQ(message(o), "--pose-select must be even, motion, spread or ga, got \"best\"");
  o = quick({0.5});
  o.pose_clip = "run";
  EXPECT_EQ(message(o), "--pose-clip run: no such clip in the mesh (1 clips)");
  o = quick({0.5});
  o.area_exponent = 1.5;
  EXPECT_EQ(message(o), "--error: the area exponent must be in [0, 1] (or -1: by the input's size), got 1.5000");
  o = quick({0.5});
  o.area_floor = -1.0;
  EXPECT_EQ(message(o), "--area-floor must be finite and >= 0");
  o = quick({0.5});
  o.max_error = 1.0;
  o.max_joints = {2};
  EXPECT_EQ(message(o).rfind("--max-error cannot be combined with --max-joints", 0), 0u);
}

TEST(MakeLods, ProgressInStagesAndCancel) {
  const SkinnedMesh leg = make_bending_cylinder(32, 64);
  std::vector<std::string> stages;
  LodCallbacks cb;
  cb.progress = [&](const char* stage, double fraction) {
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    if (stages.empty() || stages.back() != stage) stages.push_back(stage);
    return true;
  };
  make_lods(leg, quick({0.5}), cb);
  const std::vector<std::string> expected = {"choosing the example poses", "decimating", "fitting",
                                             "measuring the held-out error"};
  EXPECT_EQ(stages, expected);

  // Cancelled part-way through the decimation: no chain, and the input as it was.
  size_t calls = 0;
  cb.progress = [&](const char* stage, double) { return std::strcmp(stage, "decimating") != 0 || ++calls < 3; };
  EXPECT_THROW(make_lods(leg, quick({0.1}), cb), LodCancelled);
  EXPECT_GE(calls, 3u);
  cb.progress = [&](const char* stage, double) { return std::strcmp(stage, "measuring the held-out error") != 0; };
  EXPECT_THROW(make_lods(leg, quick({0.5}), cb), LodCancelled);
}

TEST(MakeLods, SaveWritesEveryLevelOrNone) {
  const fs::path dir = omsk_test::scratch_dir("make_lods", "save");
  const SkinnedMesh leg = make_bending_cylinder(16, 32);
  const LodChain chain = make_lods(leg, quick({0.5, 0.25}));
  const auto paths = save_lods(chain, (dir / "leg.glb").string());
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(fs::path(paths[0]).filename(), "leg_lod1.glb");
  EXPECT_EQ(fs::path(paths[1]).filename(), "leg_lod2.glb");
  for (const auto& p : paths) EXPECT_GT(fs::file_size(p), 1000u);
  EXPECT_THROW(save_lods(chain, (dir / "leg.obj").string()), IOError);
  // An output that is an input: refused, nothing written.
  EXPECT_THROW(save_lods(chain, (dir / "again.glb").string(), {paths[0], (dir / "again_lod2.glb").string()}), IOError);
  EXPECT_FALSE(fs::exists(dir / "again_lod1.glb"));
}

// The CLI is a shell around the library: its LODs are the library's, byte for byte.
TEST(MakeLods, CliWritesWhatTheLibraryMakes) {
  const fs::path dir = omsk_test::scratch_dir("make_lods", "cli");
  const std::string input = omsk_test::model("X/Testwuson.X");
  const auto r =
      omsk_test::run_command(OMSK_CLI_EXE, "'" + input + "' -o cli.glb --lods 0.5,0.2 --poses 3 --quiet", dir);
  ASSERT_EQ(r.code, 0) << r.out;

  SkinnedMesh mesh;
  import_skinned(input, mesh);
  LodOptions o;
  o.ratios = {0.5, 0.2};
  o.poses = 3;
  const auto paths = save_lods(make_lods(mesh, o), (dir / "lib.glb").string());
  ASSERT_EQ(paths.size(), 2u);
  EXPECT_EQ(bytes(dir / "cli_lod1.glb"), bytes(paths[0]));
  EXPECT_EQ(bytes(dir / "cli_lod2.glb"), bytes(paths[1]));
}

// Switch hints: the screen size below which the held-out Hausdorff error is under a pixel, in each LOD's
// report and in its glTF node's extras.
TEST(MakeLods, SwitchHintsInReportsAndFiles) {
  const SkinnedMesh leg = make_bending_cylinder(16, 32);
  const LodChain chain = make_lods(leg, quick({0.5, 0.1}));
  const auto& coarse = chain.levels[1].report;
  const auto& fine = chain.levels[0].report;
  // One pixel of a 1080-line screen: the error over the diagonal, the LOD spanning the screen's height.
  const double diagonal = bbox_diagonal(leg);
  const double error = coarse.hausdorff / 100.0 * diagonal;
  EXPECT_NEAR(coarse.switch_hint.unreal_screen_size, std::min(1.0, diagonal / (error * 1080)), 1e-12);
  EXPECT_LT(coarse.switch_hint.unreal_screen_size, 1.0);
  EXPECT_LE(coarse.switch_hint.unity_relative_height, coarse.switch_hint.unreal_screen_size);
  EXPECT_LT(coarse.switch_hint.unreal_screen_size, fine.switch_hint.unreal_screen_size)
      << "the coarser LOD is for smaller sizes";

  const fs::path dir = omsk_test::scratch_dir("make_lods", "hints");
  const auto paths = save_lods(chain, (dir / "leg.glb").string());
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, paths[1])) << err;
  const auto mesh_node =
      std::find_if(model.nodes.begin(), model.nodes.end(), [](const auto& n) { return n.mesh >= 0; });
  ASSERT_NE(mesh_node, model.nodes.end());
  const auto& extras = mesh_node->extras;
  ASSERT_TRUE(extras.Has("lod_unreal_screen_size"));
  EXPECT_NEAR(extras.Get("lod_unreal_screen_size").GetNumberAsDouble(), coarse.switch_hint.unreal_screen_size, 1e-12);
  EXPECT_NEAR(extras.Get("lod_unity_relative_screen_height").GetNumberAsDouble(),
              coarse.switch_hint.unity_relative_height, 1e-12);
  EXPECT_EQ(extras.Get("lod_hint_screen_height_px").GetNumberAsDouble(), 1080.0);
  omsk_test::expect_valid_gltf(paths[1]);
}
