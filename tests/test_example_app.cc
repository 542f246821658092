// Drives the drop-in example as a user would: its default run, a real character, and bad input.
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {
omsk_test::CommandResult run(const std::string& args, const fs::path& cwd) {
  return omsk_test::run_command(OMSK_EXAMPLE_EXE, args, cwd);
}
fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("omsk_app_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(ExampleApp, DefaultRunWritesTheLegLod) {
  const auto d = scratch();
  const auto r = run("", d);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(d / "omsk-example-out" / "leg.glb")) << r.out;
  omsk_test::expect_valid_gltf((d / "omsk-example-out" / "leg.glb").string());
}

TEST(ExampleApp, RealCharacterToGlb) {
  const auto d = scratch();
  const auto r = run(std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' w.glb 0.25 4", d);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_GT(fs::file_size(d / "w.glb"), 1000u);
  omsk_test::expect_valid_gltf((d / "w.glb").string());
}

TEST(ExampleApp, BadInputFailsWithOneLineAndNoOutput) {
  const auto d = scratch();
  for (const std::string& args :
       {std::string("no-such-file.fbx out1.glb"), std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' out2.glb 1.5",
        std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' out3.txt"}) {
    SCOPED_TRACE(args);
    const auto r = run(args, d);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  }
  for (const char* f : {"out1.glb", "out2.glb", "out3.txt"}) EXPECT_FALSE(fs::exists(d / f));
}
