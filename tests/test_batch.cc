// The batch machinery (OpenMeshSkinned/Lod/Batch.hh) driving stand-in programs: shell scripts that
// behave as the tool does (or crash, hang, fail), so that each outcome is certain and quick.
#include "run_command.hh"

#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/Lod/Batch.hh>

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {

fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("batch", name); }

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

// A stand-in for the tool: finds -o and --report among its arguments, then runs \p body.
std::string script(const fs::path& dir, const std::string& body) {
  const fs::path p = dir / "tool.sh";
  write(p,
        "#!/bin/sh\n"
        "while [ $# -gt 0 ]; do case \"$1\" in -o) out=\"$2\"; shift;; --report) rep=\"$2\"; shift;; --) "
        "in=\"$2\"; shift;; esac; shift; done\n" +
            body + "\n");
  fs::permissions(p, fs::perms::owner_all);
  return p.string();
}

// What the tool does on success: the LOD and a report naming it.
const std::string kSucceed =
    "echo ran >> \"$(dirname \"$rep\")/runs\"\n"
    "echo glb > \"$out\"\n"
    "printf '{\"triangles_in\": 100, \"lods\": [{\"ratio\": 0.5, \"faces\": 50, \"heldout_rms\": 0.25, "
    "\"heldout_hausdorff\": 1.5, \"file\": \"%s\"}]}' \"$out\" > \"$rep\"";

BatchOptions options(const std::string& exe, const fs::path& out) {
  BatchOptions o;
  o.executable = exe;
  o.out_dir = out.string();
  o.arguments = {"--ratio", "0.5"};
  return o;
}

size_t runs(const fs::path& out) {
  std::ifstream f(out / "runs");
  size_t n = 0;
  for (std::string line; std::getline(f, line);) ++n;
  return n;
}

}  // namespace

TEST(Batch, FindsWhatTheReadersTakeInPathOrderAndNamesOutputsWithoutClashes) {
  const fs::path d = scratch("find");
  for (const char* f : {"b/hero.fbx", "b/hero.glb", "a/guard.x", "walk_0001.obj", "walk_0002.obj", "walk_0003.obj",
                        "body.dae", "body_lod1.dae", "index.gltf", "Monster.mesh.xml", "notes.xml", "tex.png",
                        "readme.txt", "idle.md5anim", "guard.md5mesh", ".hidden/x.glb", ".x.glb", "out/old.glb"})
    write(d / f, "x");
  const auto in = find_inputs(d.string(), (d / "out").string());
  std::vector<std::string> names, rel;
  for (const auto& i : in) {
    names.push_back(i.name);
    rel.push_back(fs::path(i.path).lexically_relative(d).generic_string());
  }
  EXPECT_EQ(rel, (std::vector<std::string>{"Monster.mesh.xml", "a/guard.x", "b/hero.fbx", "b/hero.glb", "body.dae",
                                           "body_lod1.dae", "guard.md5mesh", "index.gltf", "walk_0001.obj"}));
  EXPECT_EQ(names, (std::vector<std::string>{"Monster", "a/guard", "b/hero.fbx", "b/hero.glb", "body", "body_lod1.dae",
                                             "guard", "index.gltf", "walk_0001"}));
  // --no-sequence: every numbered file is an asset of its own.
  EXPECT_EQ(find_inputs(d.string(), (d / "out").string(), false).size(), in.size() + 2);
  EXPECT_THROW(find_inputs((d / "tex.png").string()), IOError);
}

TEST(Batch, NamesAListOfFilesBelowTheirCommonFolder) {
  const auto in = batch_inputs({"/lib/chars/hero.fbx", "/lib/props/hero.fbx", "/lib/chars/guard.glb"});
  ASSERT_EQ(in.size(), 3u);
  EXPECT_EQ(in[0].name, "chars/hero");
  EXPECT_EQ(in[1].name, "props/hero");
  EXPECT_EQ(in[2].name, "chars/guard");
  EXPECT_EQ(batch_inputs({"/lib/chars/hero.fbx"})[0].name, "hero");
}

TEST(Batch, RunsAnAssetReadsItsReportAndSkipsItWhileUpToDate) {
  const fs::path d = scratch("skip");
  write(d / "in" / "hero.fbx", "x");
  const fs::path out = d / "out";
  BatchOptions o = options(script(d, kSucceed), out);
  const BatchInput in{(d / "in" / "hero.fbx").string(), "chars/hero"};
  AssetResult r = run_asset(in, o);
  ASSERT_EQ(r.status, AssetStatus::Ok) << r.reason;
  EXPECT_EQ(r.triangles_in, 100u);
  ASSERT_EQ(r.lods.size(), 1u);
  EXPECT_EQ(r.lods[0].triangles, 50u);
  EXPECT_DOUBLE_EQ(r.lods[0].heldout_hausdorff, 1.5);
  EXPECT_EQ(r.lods[0].file, (out / "chars/hero.glb").string());
  EXPECT_TRUE(fs::exists(out / "chars/hero.batch.json"));
  EXPECT_TRUE(fs::exists(out / "chars/hero.log"));

  AssetResult again = run_asset(in, o);
  EXPECT_EQ(again.status, AssetStatus::Skipped);
  EXPECT_EQ(again.lods[0].triangles, 50u);  // the numbers of the run that made the files
  EXPECT_EQ(runs(out / "chars"), 1u);

  o.arguments = {"--ratio", "0.25"};  // other options: run again
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Ok);
  EXPECT_EQ(runs(out / "chars"), 2u);
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Skipped);
  o.html = true;                                            // a page is wanted, and was not made
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Failed);  // the stand-in writes none: the report lacks it
  o.html = false;
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Ok);  // the failure above is not up to date either
  EXPECT_EQ(runs(out / "chars"), 4u);

  o.force = true;
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Ok);
  o.force = false;
  fs::remove(out / "chars/hero.glb");  // an output gone
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Ok);
  // The input changed after its outputs were made.
  fs::last_write_time(out / "chars/hero.glb", fs::last_write_time(in.path) - std::chrono::seconds(5));
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Ok);
  EXPECT_EQ(run_asset(in, o).status, AssetStatus::Skipped);
  EXPECT_EQ(runs(out / "chars"), 7u);
}

TEST(Batch, AFailureIsItsOneLineReasonWhateverTheCause) {
  const fs::path d = scratch("fail");
  write(d / "a.glb", "x");
  const BatchInput in{(d / "a.glb").string(), "a"};
  struct Case {
    std::string body, reason;
  };
  const Case cases[] = {
      {"echo 'table' ; echo 'skinned-decimate: warning: w' >&2; echo 'skinned-decimate: a.glb: not a glTF' >&2; "
       "echo 'skinned-decimate: warning: later' >&2; exit 1",
       "a.glb: not a glTF"},
      {"echo 'skinned-decimate: error: --faces 9 is more than the input has' >&2; exit 2",
       "--faces 9 is more than the input has"},
      {"exit 3", "exited with code 3 without a message (see " + (d / "out" / "a.log").string() + ")"},
      {"kill -SEGV $$", "crashed (signal 11: Segmentation fault)"},
      {"echo glb > \"$out\"", "its report " + (d / "out" / "a.report.json").string() + " cannot be read"},
      {"printf '{\"lods\": 3}' > \"$rep\"", "its report " + (d / "out" / "a.report.json").string() + " has no LODs"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.body);
    const AssetResult r = run_asset(in, options(script(d, c.body), d / "out"));
    EXPECT_EQ(r.status, AssetStatus::Failed);
    EXPECT_EQ(r.reason, c.reason);
  }
  EXPECT_THROW(run_asset(in, options((d / "no-such-program").string(), d / "out")), IOError);
}

TEST(Batch, AKilledChildLeavesNoStagedFilesAndAHungOneIsStoppedWithWhatItStarted) {
  const fs::path d = scratch("kill");
  write(d / "a.glb", "x");
  const BatchInput in{(d / "a.glb").string(), "a"};
  AssetResult r = run_asset(in, options(script(d,
                                               "touch \"$(dirname \"$out\")/.a.omsk-$$-0.glb\"; "
                                               "touch \"$(dirname \"$out\")/.a.omsk-1-0.glb\"; kill -KILL $$"),
                                        d / "out"));
  EXPECT_EQ(r.reason, "crashed (signal 9: Killed)");
  size_t staged = 0;
  for (const auto& e : fs::directory_iterator(d / "out"))
    staged += e.path().filename().string().find(".omsk-") != std::string::npos;
  EXPECT_EQ(staged, 1u);  // only the other process's

  BatchOptions o = options(script(d, "sleep 30 & echo $! > \"$(dirname \"$out\")/grandchild\"; sleep 30"), d / "out");
  o.asset_time_limit = 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  r = run_asset(in, o);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  EXPECT_EQ(r.reason, "timed out after 0.5 s");
  const pid_t grandchild = std::stoi(read(d / "out/grandchild"));
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {  // reparented and reaped by init
    gone = ::kill(grandchild, 0) != 0;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(gone) << "the hung asset's own child was left running";
}

TEST(Batch, RunsJobsAtOnceReportsProgressAndCanBeCancelled) {
  const fs::path d = scratch("jobs");
  for (const char* f : {"a.glb", "b.glb", "c.glb", "d.glb"}) write(d / "in" / f, "x");
  // Each waits (1.5 s and more) until another has started: only two at once finish in time.
  const std::string meet =
      "touch \"$(dirname \"$out\")/started.$$\"; i=0; while [ $(ls \"$(dirname \"$out\")\" | grep -c started) -lt 2 "
      "] && [ $i -lt 15 ]; do sleep 0.1; i=$((i+1)); done; [ $i -lt 15 ] || exit 9\n" +
      kSucceed;
  auto forget_starts = [&] {
    for (const auto& e : fs::directory_iterator(d / "out"))
      if (e.path().filename().string().rfind("started.", 0) == 0) fs::remove(e.path());
  };
  BatchOptions o = options(script(d, meet), d / "out");
  o.jobs = 2;
  const auto inputs = find_inputs((d / "in").string());
  std::vector<std::string> lines;
  auto results = run_batch(inputs, o, [&](const BatchProgress& p) {
    lines.push_back(progress_line(p));
    return true;
  });
  ASSERT_EQ(results.size(), 4u);
  for (const auto& r : results) EXPECT_EQ(r.status, AssetStatus::Ok) << r.name << ": " << r.reason;
  EXPECT_EQ(results[2].name, "c");  // in the order of the inputs, whatever order they ended in
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines.back(), "batch: 4/4 done, 0 failed, 0 skipped");

  forget_starts();
  o.force = true;
  o.jobs = 1;
  results = run_batch(inputs, o, [](const BatchProgress&) { return false; });
  ASSERT_EQ(results.size(), 4u);
  // With one job the first waits for a partner that never starts (exit 9), and then the batch is cancelled.
  EXPECT_EQ(results[0].status, AssetStatus::Failed);
  EXPECT_EQ(results[0].reason, "exited with code 9 without a message (see " + results[0].log + ")");
  for (size_t i = 1; i < 4; ++i) EXPECT_EQ(results[i].reason, "cancelled");

  // A cancelled asset keeps what it had (the outputs of the first run, up to date); the failed one runs
  // again, alone, and fails again.
  forget_starts();
  o.force = false;
  o.jobs = 2;
  results = run_batch(inputs, o);
  EXPECT_EQ(results[0].status, AssetStatus::Failed);
  for (size_t i = 1; i < 4; ++i) EXPECT_EQ(results[i].status, AssetStatus::Skipped) << results[i].reason;
  EXPECT_THROW(run_batch({inputs[0], inputs[0]}, o), IOError);
}

TEST(Batch, SummaryListsEveryAssetWithItsNumbersOrReason) {
  const fs::path d = scratch("summary");
  write(d / "in/a.glb", "x");
  write(d / "in/b <&>.glb", "x");
  const std::string fail = "echo 'skinned-decimate: b <&>.glb: not a <glTF>' >&2; exit 1";
  BatchOptions o = options(script(d, "case \"$in\" in *a.glb) ;; *) " + fail + ";; esac\n" + kSucceed), d / "out");
  const auto results = run_batch(find_inputs((d / "in").string()), o);
  write_summary(results, o);
  const nlohmann::json s = omsk_test::read_json(d / "out/summary.json");
  EXPECT_EQ(s["assets"], 2);
  EXPECT_EQ(s["ok"], 1);
  EXPECT_EQ(s["failed"], 1);
  EXPECT_EQ(s["arguments"], nlohmann::json({"--ratio", "0.5"}));
  EXPECT_EQ(s["results"][0]["lods"][0]["file"], "a.glb");  // from the summary's folder
  EXPECT_EQ(s["results"][0]["log"], "a.log");
  EXPECT_EQ(s["results"][1]["status"], "failed");
  EXPECT_EQ(s["results"][1]["reason"], "b <&>.glb: not a <glTF>");
  EXPECT_TRUE(s["results"][0]["lods"][0]["heldout_rms"].is_number());
  const std::string page = read(d / "out/index.html");
  EXPECT_NE(page.find("b &lt;&amp;&gt;.glb: not a &lt;glTF&gt;"), std::string::npos) << page;
  EXPECT_NE(page.find("href=\"b%20%3C%26%3E.log\""), std::string::npos) << page;
  EXPECT_NE(page.find("1 ok, 1 failed, 0 skipped"), std::string::npos) << page;
  for (const auto& e : fs::directory_iterator(d / "out"))
    EXPECT_NE(e.path().filename().string()[0], '.') << "staged file left: " << e.path();
}

TEST(Batch, AResultCrossesAProcessBoundaryAsJson) {
  AssetResult r;
  r.input = "in/a.glb";
  r.name = "a";
  r.status = AssetStatus::Skipped;
  r.reason = "up to date";
  r.seconds = 1.25;
  r.triangles_in = 10;
  r.lods.push_back({0.5, 5, 0.1, std::nan(""), "out/a.glb"});
  r.log = "out/a.log";
  const AssetResult b = parse_asset_result(asset_result_json(r));
  EXPECT_EQ(asset_result_json(b), asset_result_json(r));
  EXPECT_TRUE(std::isnan(b.lods[0].heldout_hausdorff));
  EXPECT_THROW(parse_asset_result("{\"input\": 1}"), IOError);
  EXPECT_THROW(parse_asset_result("not json"), IOError);
}
