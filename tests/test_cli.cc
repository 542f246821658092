// Drives skinned-decimate as a technical artist would.
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {
omsk_test::CommandResult cli(const std::string& args, const fs::path& cwd) {
  return omsk_test::run_command(OMSK_CLI_EXE, args, cwd);
}
fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("cli", name); }
const std::string wuson = std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X'";
}  // namespace

TEST(Cli, LodChainWithReportOnARealCharacter) {
  const auto d = scratch("chain");
  const auto r = cli(wuson + " -o w.glb --lods 0.5,0.25,0.1 --max-influences 4 --poses 8 --report w.json --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "w.json");
  ASSERT_EQ(rep["lods"].size(), 3u);
  size_t prev_faces = SIZE_MAX;
  double prev_rms = -1.0;
  for (int i = 0; i < 3; ++i) {
    const auto& l = rep["lods"][i];
    const fs::path file = d / ("w_lod" + std::to_string(i + 1) + ".glb");
    omsk_test::expect_valid_gltf(file.string());
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_LT(l["faces"].get<size_t>(), prev_faces);
    EXPECT_LE(l["max_influences"].get<int>(), 4);
    EXPECT_GT(l["heldout_rms"].get<double>(), prev_rms);
    EXPECT_EQ(l["example_pose_times"].size(), 8u);
    EXPECT_GT(l["heldout_times"].size(), 0u);
    prev_faces = l["faces"];
    prev_rms = l["heldout_rms"];
    // The LOD is a valid glTF with the skeleton, the skin and every clip.
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err;
    EXPECT_EQ(m.skins.size(), 1u);
    EXPECT_EQ(m.animations.size(), 3u);
    EXPECT_GT(m.skins[0].joints.size(), 10u);
  }
  EXPECT_NE(r.out.find("heldout RMS%"), std::string::npos) << r.out;
}

TEST(Cli, FacesTargetAndStaticMethod) {
  const auto d = scratch("faces");
  const auto r = cli(wuson + " -o s.gltf --faces 1000 --method static --quiet --report s.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "s.json");
  EXPECT_NEAR(rep["lods"][0]["faces"].get<double>(), 1000.0, 2.0);
  EXPECT_TRUE(fs::exists(d / "s.gltf"));
}

TEST(Cli, BadInputGivesOneLineErrorNonZeroExitAndNoFiles) {
  const auto d = scratch("bad");
  fs::create_directories(d / "ro");
  std::ofstream(d / "plainfile") << "x";
  const std::vector<std::string> cases = {
      wuson + " -o a.glb --bogus",
      wuson + " -o a.glb --ratio 0",
      wuson + " -o a.glb --ratio 1.5",
      wuson + " -o a.glb --faces 999999",
      wuson + " -o a.glb --max-influences 0",
      wuson + " -o a.glb --poses -1",
      wuson + " -o a.glb --pose-clip NoSuchClip",
      wuson + " -o a.glb --lods 0.5,2",
      wuson + " -o a.obj",
      wuson + " -o plainfile/a.glb",
      wuson + " -o no/such/dir/a.glb",
      wuson,
      "no-such-file.fbx -o a.glb",
      wuson + " -o a.glb --ratio 0.5 --faces 100",
  };
  for (const auto& args : cases) {
    SCOPED_TRACE(args);
    const auto r = cli(args, d);
    EXPECT_NE(r.code, 0) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  }
  for (const auto& e : fs::recursive_directory_iterator(d))
    EXPECT_TRUE(e.path().filename() == "plainfile" || e.path().filename() == "ro") << e.path();
}

TEST(Cli, NoAnimationWithPosesExplainsAndRunsInRestPose) {
  const auto d = scratch("static");
  std::ofstream(d / "tet.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n"
                                  "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 5\nf 3 4 5\nf 4 2 5\n";
  const auto r = cli("tet.obj -o t.glb --ratio 1 --poses 4", d);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("no animation"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rest pose only"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(d / "t.glb"));
  omsk_test::expect_valid_gltf((d / "t.glb").string());
}

TEST(Cli, ThreadCountChangesNothingAndNoEvalSkipsOnlyTheError) {
  const auto d = scratch("threads");
  nlohmann::json rep[3];
  const char* extra[3] = {"--threads 1", "--threads 2", "--threads 2 --no-eval"};
  for (int i = 0; i < 3; ++i) {
    const auto r = cli(wuson + " -o w" + std::to_string(i) + ".glb --lods 0.5,0.2 --report r" + std::to_string(i) +
                           ".json --quiet " + extra[i],
                       d);
    ASSERT_EQ(r.code, 0) << r.out;
    rep[i] = omsk_test::read_json(d / ("r" + std::to_string(i) + ".json"));
    if (i == 2) {
      EXPECT_NE(r.out.find("             -              -"), std::string::npos) << r.out;
    }
  }
  for (int l = 0; l < 2; ++l) {
    EXPECT_EQ(rep[0]["lods"][l]["faces"], rep[1]["lods"][l]["faces"]);
    EXPECT_EQ(rep[0]["lods"][l]["heldout_rms"], rep[1]["lods"][l]["heldout_rms"]) << "evaluation depends on threads";
    EXPECT_EQ(rep[0]["lods"][l]["heldout_hausdorff"], rep[1]["lods"][l]["heldout_hausdorff"]);
    EXPECT_GT(rep[0]["lods"][l]["heldout_rms"].get<double>(), 0.0);
    EXPECT_EQ(rep[2]["lods"][l]["faces"], rep[1]["lods"][l]["faces"]);
    EXPECT_TRUE(rep[2]["lods"][l]["heldout_rms"].is_null());
  }
  // The same LOD files whatever the thread count (the decimation does not depend on it).
  for (const char* lod : {"_lod1.glb", "_lod2.glb"}) {
    std::ifstream a(d / (std::string("w0") + lod), std::ios::binary),
        b(d / (std::string("w1") + lod), std::ios::binary);
    const std::string sa((std::istreambuf_iterator<char>(a)), {}), sb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(sa.empty());
    EXPECT_EQ(sa, sb) << lod;
  }
  EXPECT_GT(rep[0]["seconds"]["evaluate"].get<double>(), 0.0);
  EXPECT_GT(rep[0]["import_seconds"].get<double>(), 0.0);
}

TEST(Cli, AnimErrorThinsTheClipsOfEveryLodWithinItsBound) {
  const auto d = scratch("anim");
  nlohmann::json rep[2];
  for (int i = 0; i < 2; ++i) {
    const auto r = cli(wuson + " -o a" + std::to_string(i) + ".glb --lods 0.5,0.25 --report r" + std::to_string(i) +
                           ".json --quiet" + (i ? " --anim-error 0.1" : ""),
                       d);
    ASSERT_EQ(r.code, 0) << r.out;
    rep[i] = omsk_test::read_json(d / ("r" + std::to_string(i) + ".json"));
  }
  for (int l = 0; l < 2; ++l) {
    const auto &full = rep[0]["lods"][l], &thin = rep[1]["lods"][l];
    EXPECT_LT(thin["keys"].get<size_t>(), full["keys"].get<size_t>() * 6 / 10);
    EXPECT_EQ(thin["faces"], full["faces"]);
    // Each vertex moves by at most 0.1% of the diagonal in the clips' frames: the held-out error barely moves.
    EXPECT_LT(thin["heldout_rms"].get<double>(), 1.1 * full["heldout_rms"].get<double>());
    const fs::path file = d / ("a1_lod" + std::to_string(l + 1) + ".glb");
    omsk_test::expect_valid_gltf(file.string());
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err;
    EXPECT_EQ(m.animations.size(), 3u);  // every clip kept, thinner
  }
}

TEST(Cli, MaxJointsWritesLodsWithTheReducedSkeletonThatStillPlayEveryClip) {
  const auto d = scratch("joints");
  const auto r =
      cli(wuson + " -o j.glb --lods 0.5,0.25 --max-joints 30,24 --anim-error 0.15 --report j.json --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "j.json");
  for (int l = 0; l < 2; ++l) {
    const int budget = l == 0 ? 30 : 24;  // one per LOD, largest LOD first
    EXPECT_LE(rep["lods"][l]["joints"].get<int>(), budget);
    EXPECT_GT(rep["lods"][l]["joints"].get<int>(), budget - 3);
    EXPECT_GT(rep["lods"][l]["heldout_rms"].get<double>(), 0.0);
    const fs::path file = d / ("j_lod" + std::to_string(l + 1) + ".glb");
    omsk_test::expect_valid_gltf(file.string());
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err;
    ASSERT_EQ(m.skins.size(), 1u);
    EXPECT_LE(m.skins[0].joints.size(), size_t(budget));
    EXPECT_EQ(m.animations.size(), 3u);
  }
}

TEST(Cli, TheFoldOverLimitIsRelaxedToComeCloserToTheTargetUnlessStrict) {
  // Quake's sydney (a frame animation): at 20 triangles every collapse left folds a face in some frame.
  const auto d = scratch("fold");
  const std::string sydney = std::string("'") + OMSK_TEST_MODELS + "/MD2/sydney.md2'";
  nlohmann::json rep[2];
  for (int i = 0; i < 2; ++i) {
    const auto r = cli(sydney + " -o f" + std::to_string(i) + ".glb --faces 20 --no-eval --report f" +
                           std::to_string(i) + ".json" + (i ? " --strict-fold" : ""),
                       d);
    ASSERT_EQ(r.code, 0) << r.out;
    rep[i] = omsk_test::read_json(d / ("f" + std::to_string(i) + ".json"));
    if (i == 0) {
      EXPECT_NE(r.out.find("the fold-over limit was relaxed to"), std::string::npos) << r.out;
    }
  }
  const auto &relaxed = rep[0]["lods"][0], &strict = rep[1]["lods"][0];
  EXPECT_GT(relaxed["fold_limit_deg"].get<double>(), 90.0);
  EXPECT_EQ(strict["fold_limit_deg"].get<double>(), 90.0);
  EXPECT_LT(relaxed["faces"].get<size_t>(), strict["faces"].get<size_t>());
  omsk_test::expect_valid_gltf((d / "f0.glb").string());
}

TEST(Cli, ATargetBelowWhatTheTopologyAllowsStopsThereAndSaysWhy) {
  // Testwuson is 68 pieces (horns, eyes, teeth...): open ones end as single triangles or strips, closed ones
  // as tetrahedra. Past that no collapse keeps the mesh manifold, and the table says so instead of blaming
  // the modules.
  const auto d = scratch("floor");
  const auto r = cli(wuson + " -o f.glb --faces 10 --no-eval --no-refit --report f.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto lod = omsk_test::read_json(d / "f.json")["lods"][0];
  EXPECT_FALSE(lod["target_reached"].get<bool>());
  EXPECT_TRUE(lod["at_topology_floor"].get<bool>());
  EXPECT_GT(lod["faces"].get<size_t>(), 68u);
  EXPECT_NE(r.out.find("no collapse is left that keeps the mesh manifold (68 pieces)"), std::string::npos) << r.out;
  // The strict run already got there: nothing is relaxed, and the table does not claim it was.
  EXPECT_EQ(lod["fold_limit_deg"].get<double>(), 90.0);
  EXPECT_EQ(r.out.find("relaxed"), std::string::npos) << r.out;
  // Half the triangles: reached, nowhere near the floor.
  const auto h = cli(wuson + " -o h.glb --ratio 0.5 --no-eval --no-refit --report h.json --quiet", d);
  ASSERT_EQ(h.code, 0) << h.out;
  const auto half = omsk_test::read_json(d / "h.json")["lods"][0];
  EXPECT_TRUE(half["target_reached"].get<bool>());
  EXPECT_FALSE(half["at_topology_floor"].get<bool>());
  EXPECT_EQ(half["fold_fallbacks"].get<size_t>(), 0u) << "the fallback placements are for a target out of reach";
}

TEST(Cli, MaxErrorBoundsEveryLodAndStopsWhereTheBoundWould) {
  const auto d = scratch("max_error");
  const auto r = cli(wuson + " -o b.glb --lods 0.5,0.1 --max-error 0.5 --no-eval --report b.json --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "b.json");
  const auto &half = rep["lods"][0], &tenth = rep["lods"][1];
  // Half the triangles go within the bound; a tenth would need cuts further than 0.5% of the diagonal.
  EXPECT_TRUE(half["target_reached"].get<bool>());
  EXPECT_FALSE(tenth["target_reached"].get<bool>());
  EXPECT_LT(tenth["faces"].get<size_t>(), half["faces"].get<size_t>());
  for (const auto& l : rep["lods"]) {
    EXPECT_LE(l["deviation_bound"].get<double>(), 0.5);
    EXPECT_EQ(l["fold_limit_deg"].get<double>(), 90.0) << "the bound goes before the count";
  }
  EXPECT_NE(r.out.find("exceed --max-error"), std::string::npos) << r.out;
  omsk_test::expect_valid_gltf((d / "b_lod2.glb").string());
  // Without it, no bound is reported.
  const auto f = cli(wuson + " -o f.glb --ratio 0.5 --no-eval --no-refit --report f.json --quiet", d);
  ASSERT_EQ(f.code, 0) << f.out;
  rep = omsk_test::read_json(d / "f.json");
  EXPECT_TRUE(rep["lods"][0]["deviation_bound"].is_null());
  // The frame methods place vertices themselves: a bound they would not keep is refused, not ignored.
  const auto m = cli(std::string("'") + OMSK_TEST_MODELS + "/MD2/faerie.md2' -o m.glb --max-error 1 --quiet", d);
  EXPECT_NE(m.code, 0);
  EXPECT_NE(m.out.find("--max-error"), std::string::npos) << m.out;
  EXPECT_FALSE(fs::exists(d / "m.glb"));
  // Nor can the skeleton LoD re-solve the skins after the bound was kept.
  const auto j = cli(wuson + " -o j.glb --max-error 1 --max-joints 20 --quiet", d);
  EXPECT_EQ(j.code, 2);
  EXPECT_NE(j.out.find("--max-joints"), std::string::npos) << j.out;
  EXPECT_FALSE(fs::exists(d / "j.glb"));
}
