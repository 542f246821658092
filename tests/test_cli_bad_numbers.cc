// skinned-decimate on corrupt numbers (the families the mutation runs found): a NaN animation key, a huge
// one, a joint index outside the skin, an accessor that claims 2^31 elements. Each ends within a minute,
// either as one exact line naming the value (exit 1) or as a file the validator passes, never as a hang
// or a flood of messages.
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const std::string kModels = OMSK_TEST_MODELS;

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
void write(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

// Testwuson with the first occurrence of \p from replaced by \p to, in a fresh folder.
fs::path wuson_with(const std::string& test, const std::string& from, const std::string& to) {
  const fs::path d = omsk_test::scratch_dir("badnum", test);
  std::string x = read(kModels + "/X/Testwuson.X");
  const size_t at = x.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  write(d / "in.x", x.replace(at, from.size(), to));
  return d;
}

// The CLI under `timeout`, so that a hang fails the test (exit 124) instead of stalling the suite.
omsk_test::CommandResult run(const fs::path& d, const std::string& input, const std::string& extra = "") {
  return omsk_test::run_command(
      "/usr/bin/timeout",
      "60 '" + std::string(OMSK_CLI_EXE) + "' " + input + " -o out.glb --ratio 0.5 --poses 2 --quiet " + extra, d);
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream is(s);
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

// The first animation of Testwuson: clip "Wuson_Run". Its first channel moves the node "Wuson", the skinned
// mesh's own node, which is no joint (glTF's rule: it moves nothing); its second moves the root bone "Root",
// whose first translation key is this one.
const std::string kFirstRootPosKey = "0;3;0.000000,0.522834,0.009935;;,";

}  // namespace

TEST(CliBadNumbers, ANaNKeyIsOneLineNamingClipJointAndKey) {
  const fs::path d = wuson_with("nan_key", kFirstRootPosKey, "0;3;NaN,0.522834,0.009935;;,");
  const auto r = run(d, "in.x");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(r.out,
            "skinned-decimate: in.x: clip \"Wuson_Run\": joint \"Root\": translation key 0 has the non-finite "
            "value nan\n");
  EXPECT_FALSE(fs::exists(d / "out.glb"));
}

TEST(CliBadNumbers, AHugeKeyEndsWithAValidFile) {
  // 4294967296 is finite and a float: a legal if absurd scale of the root, which blows every posed
  // coordinate up to 1e9 and the solves' Gram matrices towards overflow.
  const std::string root_scale = "   0;3;1.000000,1.000000,1.000000;;;\n  }\n\n  AnimationKey pos {\n   2;\n   30;";
  std::string huge = root_scale;
  huge.replace(huge.find("1.000000"), 8, "4294967296.000000");
  const fs::path d = wuson_with("huge_key", root_scale, huge);
  const auto r = run(d, "in.x");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_LE(r.out.size(), 4096u) << r.out;
  omsk_test::expect_valid_gltf((d / "out.glb").string());
}

TEST(CliBadNumbers, AJointOutsideTheSkinIsOneLineNamingIt) {
  // simple_skin's skin has 2 joints; vertex 4 weighs its second joint by 0.5 (JOINTS_0: bufferView 2, stride 16).
  const fs::path d = omsk_test::scratch_dir("badnum", "joint");
  tinygltf::Model m = omsk_spec::load(kModels + "/glTF2/simple_skin/simple_skin.gltf");
  const uint16_t bad = 7;
  std::memcpy(m.buffers[m.bufferViews[2].buffer].data.data() + m.bufferViews[2].byteOffset + 4 * 16 + 2, &bad, 2);
  omsk_spec::save_glb(m, (d / "in.glb").string());
  const auto r = run(d, "in.glb");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(r.out,
            "skinned-decimate: in.glb: vertex 4 of mesh 0 (\"\") names joint 7 in JOINTS_0, but skin 0 (\"\") "
            "has 2 joints\n");
}

TEST(CliBadNumbers, AnAccessorOfTwoToTheThirtyFirstElementsIsOneLineNamingIt) {
  const fs::path d = omsk_test::scratch_dir("badnum", "accessor");
  tinygltf::Model m = omsk_spec::load(kModels + "/glTF2/simple_skin/simple_skin.gltf");
  m.accessors[3].count = size_t(1) << 31;  // WEIGHTS_0
  omsk_spec::save_glb(m, (d / "in.glb").string());
  const auto r = run(d, "in.glb");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(r.out,
            "skinned-decimate: in.glb: accessor 3 (WEIGHTS_0 of mesh 0 (\"\")) claims 2147483648 elements of "
            "16 bytes from byte 160, more than its buffer view's 320 bytes hold\n");
}

TEST(CliBadNumbers, BytesThatAreNoTextNeverReachTheTerminal) {
  // A clip name of invalid UTF-8 and a terminal escape: the warning and the file carry '?' instead.
  const fs::path d = wuson_with("names", "AnimationSet Wuson_Run {", "AnimationSet Wuson_\xff\x1b[2J {");
  const auto r = run(d, "in.x");
  ASSERT_EQ(r.code, 0) << r.out;
  for (const std::string& l : lines(r.out))
    for (unsigned char c : l) EXPECT_TRUE(c >= 0x20 && c != 0x7f && c != 0xff) << l;
  EXPECT_NE(r.out.find("names were not printable UTF-8"), std::string::npos) << r.out;
  const tinygltf::Model out = omsk_spec::load((d / "out.glb").string());
  bool found = false;
  for (const auto& a : out.animations) found |= a.name == "Wuson_??[2J";
  EXPECT_TRUE(found);
  omsk_test::expect_valid_gltf((d / "out.glb").string());
}
