// skinned-decimate batch over a small library: real characters, a still mesh, a corrupt file and one that
// crashes its reader; resumed, rerun with other options, and refused when the command line is wrong.
#include "fixtures.hh"
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace fs = std::filesystem;

namespace {

omsk_test::CommandResult cli(const std::string& args, const fs::path& cwd) {
  return omsk_test::run_command(OMSK_CLI_EXE, args, cwd);
}

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

std::string last_line(const std::string& out) {
  std::string s = out;
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s.substr(s.rfind('\n') == std::string::npos ? 0 : s.rfind('\n') + 1);
}

// lib/wuson.x, lib/chars/wuson.glb (the same character as glTF), lib/props/tet.obj (a still mesh),
// lib/broken.glb (not a glTF) and lib/crash.md5mesh (crashes assimp's reader).
fs::path library(const std::string& name) {
  const fs::path d = omsk_test::scratch_dir("cli_batch", name);
  fs::create_directories(d / "lib/chars");
  fs::create_directories(d / "lib/props");
  fs::copy_file(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", d / "lib/wuson.x");
  omsk_fixtures::testwuson(d.string());
  fs::rename(d / "testwuson_tidy.glb", d / "lib/chars/wuson.glb");
  std::ofstream(d / "lib/props/tet.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n"
                                            "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 5\nf 3 4 5\nf 4 2 5\n";
  std::ofstream(d / "lib/broken.glb") << "glTF this is not";
  fs::copy_file(std::string(OMSK_TEST_DATA) + "/crashers/md5_mutant_segv_1.md5mesh", d / "lib/crash.md5mesh");
  return d;
}

const std::string kOptions = " --ratio 0.5 --poses 2 --max-influences 4 --quiet";

std::map<std::string, nlohmann::json> by_name(const nlohmann::json& summary) {
  std::map<std::string, nlohmann::json> m;
  for (const auto& r : summary["results"]) m[r["name"]] = r;
  return m;
}

}  // namespace

TEST(CliBatch, RunsALibraryReportsFailuresInOneLineAndResumes) {
  const fs::path d = library("run");
  auto r = cli("batch lib -o out --jobs 2" + kOptions, d);
  ASSERT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(last_line(r.out), "batch: 2 of 5 assets failed; summary: out/index.html") << r.out;
  EXPECT_NE(r.out.find("batch: 5/5 done, 2 failed, 0 skipped ("), std::string::npos) << r.out;

  const nlohmann::json s = omsk_test::read_json(d / "out/summary.json");
  EXPECT_EQ(s["assets"], 5);
  EXPECT_EQ(s["ok"], 3);
  EXPECT_EQ(s["failed"], 2);
  EXPECT_EQ(s["arguments"], nlohmann::json({"--ratio", "0.5", "--max-influences", "4", "--poses", "2", "--quiet"}));
  auto res = by_name(s);
  ASSERT_EQ(res.size(), 5u);
  EXPECT_EQ(res["broken"]["status"], "failed");
  const std::string broken = res["broken"]["reason"];
  EXPECT_EQ(broken.find("lib/broken.glb: "), 0u) << broken;
  EXPECT_EQ(res["crash"]["status"], "failed");
  EXPECT_NE(res["crash"]["reason"].get<std::string>().find("the reader crashed"), std::string::npos) << res["crash"];
  for (const char* name : {"wuson", "chars/wuson", "props/tet"}) {
    SCOPED_TRACE(name);
    const auto& a = res[name];
    ASSERT_EQ(a["status"], "ok") << a;
    ASSERT_EQ(a["lods"].size(), 1u);
    const auto& lod = a["lods"][0];
    EXPECT_EQ(lod["file"], std::string(name) + ".glb");
    EXPECT_LE(lod["triangles"].get<size_t>(), a["triangles_in"].get<size_t>() / 2 + 1);
    omsk_test::expect_valid_gltf((d / "out" / lod["file"].get<std::string>()).string());
    EXPECT_TRUE(fs::exists(d / "out" / a["report"].get<std::string>()));
    EXPECT_TRUE(fs::exists(d / "out" / a["log"].get<std::string>()));
  }
  // The characters are judged in held-out frames; the still mesh has none to be judged in.
  EXPECT_GT(res["wuson"]["lods"][0]["heldout_rms"].get<double>(), 0.0);
  // The same character as .x and as .glb: the same target; the order the reader gives the vertices in may
  // end the decimation one border collapse apart.
  EXPECT_NEAR(res["wuson"]["lods"][0]["triangles"].get<double>(),
              res["chars/wuson"]["lods"][0]["triangles"].get<double>(), 1.0);

  const std::string page = read(d / "out/index.html");
  for (const char* input :
       {"lib/wuson.x", "lib/chars/wuson.glb", "lib/props/tet.obj", "lib/broken.glb", "lib/crash.md5mesh"})
    EXPECT_NE(page.find(input), std::string::npos) << input;
  EXPECT_NE(page.find("3 ok, 2 failed, 0 skipped"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"reason\" colspan=\"2\">lib/broken.glb: "), std::string::npos) << page;
  // As a browser shows it: a row per asset, the failures' reasons, every link leading to a file.
  const auto shown = omsk_test::run_command(
      "node", "'" + std::string(OMSK_SOURCE_DIR) + "/tests/browser/check-batch-index.mjs' out/index.html 3 2 0", d);
  if (shown.code != 77) {
    EXPECT_EQ(shown.code, 0) << shown.out;
  }

  // Again: the three that succeeded are up to date, with their numbers; the failures run again.
  const auto lod_time = fs::last_write_time(d / "out/wuson.glb");
  r = cli("batch lib -o out --jobs 2" + kOptions, d);
  ASSERT_EQ(r.code, 1) << r.out;
  const nlohmann::json again = omsk_test::read_json(d / "out/summary.json");
  EXPECT_EQ(again["skipped"], 3);
  EXPECT_EQ(again["failed"], 2);
  auto res2 = by_name(again);
  EXPECT_EQ(res2["wuson"]["status"], "skipped");
  EXPECT_EQ(res2["wuson"]["lods"], res["wuson"]["lods"]);
  EXPECT_EQ(fs::last_write_time(d / "out/wuson.glb"), lod_time);
  EXPECT_EQ(res2["broken"]["reason"], res["broken"]["reason"]);

  // Another option, and pages: every asset runs again.
  fs::remove(d / "lib/broken.glb");
  fs::remove(d / "lib/crash.md5mesh");
  r = cli("batch lib -o out --html --ratio 0.25 --poses 2 --quiet --no-eval", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(last_line(r.out), "batch: all 3 assets ok (0 skipped, up to date); summary: out/index.html");
  const nlohmann::json third = omsk_test::read_json(d / "out/summary.json");
  EXPECT_EQ(third["ok"], 3);
  auto res3 = by_name(third);
  EXPECT_LT(res3["wuson"]["lods"][0]["triangles"], res["wuson"]["lods"][0]["triangles"]);
  EXPECT_TRUE(res3["wuson"]["lods"][0]["heldout_rms"].is_null());
  EXPECT_EQ(res3["chars/wuson"]["page"], "chars/wuson.html");
  EXPECT_TRUE(fs::exists(d / "out/chars/wuson.html"));
  EXPECT_NE(read(d / "out/index.html").find("<a href=\"chars/wuson.html\">lib/chars/wuson.glb</a>"), std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(d / "out"))
    EXPECT_NE(e.path().filename().string()[0], '.') << "staged file left: " << e.path();
}

TEST(CliBatch, OptionsWithoutMeaningPerAssetAreRefusedInOneLine) {
  const fs::path d = omsk_test::scratch_dir("cli_batch", "usage");
  fs::create_directories(d / "lib");
  fs::create_directories(d / "empty");
  fs::copy_file(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", d / "lib/wuson.x");
  const std::pair<std::string, std::string> cases[] = {
      {"batch lib -o out --report r.json", "--report"},
      {"batch lib -o out --preview p.png", "--preview"},
      {"batch lib -o out --segment s.glb", "--segment"},
      {"--html page.html batch lib -o out", "--html"},
      {"lib/wuson.x batch lib -o out", "INPUT"},
      {"batch lib", "--output"},
      {"batch lib -o out --bogus", "--bogus"},
      {"batch lib -o out --jobs 0", "--jobs"},
      {"batch no-such-dir -o out", "no-such-dir"},
      {"batch empty -o out", "holds no file a reader takes"},
      {"batch lib -o lib", "is IN_DIR itself"},
      // Values the library refuses: refused once, before any asset runs.
      {"batch lib -o out --lods 0.5,1.5", "--lods: every ratio must be in (0, 1]"},
      {"batch lib -o out --max-error 1 --max-joints 5", "--max-error cannot be combined"},
  };
  for (const auto& [args, says] : cases) {
    SCOPED_TRACE(args);
    const auto r = cli(args, d);
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_NE(r.out.find(says), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(d / "out"));
  const auto help = cli("batch --help", d);
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("--jobs"), std::string::npos) << help.out;
  EXPECT_NE(cli("--help", d).out.find("batch"), std::string::npos);
}
