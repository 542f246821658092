// skinned-decimate in careless and hostile hands: inputs untouched byte for byte, nothing half-written,
// one-line errors with the documented exit codes, and no data changed without a word.
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fs = std::filesystem;

namespace {
omsk_test::CommandResult cli(const std::string& args, const fs::path& cwd) {
  return omsk_test::run_command(OMSK_CLI_EXE, args, cwd);
}
fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("protect", name); }
std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
std::vector<std::string> files_in(const fs::path& d) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}
// Error lines (not warnings) in the output: a refusal must say why in exactly one.
int error_lines(const std::string& out) {
  std::istringstream is(out);
  int n = 0;
  for (std::string l; std::getline(is, l);)
    n += l.rfind("skinned-decimate: ", 0) == 0 && l.find(": warning: ") == std::string::npos;
  return n;
}
const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";

// A folder holding a copy of a small skinned glTF named \p name.
fs::path with_input(const std::string& test, const std::string& name) {
  const auto d = scratch(test);
  fs::copy_file(simple_skin, d / name);
  return d;
}

void expect_refused(const std::string& args, const fs::path& d, const std::string& input, const std::string& why) {
  const std::string before = read(d / input);
  const auto files = files_in(d);
  const auto r = cli(args, d);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
  EXPECT_EQ(error_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find(why), std::string::npos) << r.out;
  EXPECT_EQ(read(d / input), before) << "input changed by: " << args;
  EXPECT_EQ(files_in(d), files) << "files added or removed by: " << args;
}
}  // namespace

TEST(CliProtection, OutputThatIsTheInput) {
  const auto d = with_input("o_is_input", "in.gltf");
  expect_refused("in.gltf -o in.gltf --quiet", d, "in.gltf", "is the input");
  expect_refused("in.gltf -o ./sub/../in.gltf --quiet", d, "in.gltf", "is the input");
}

TEST(CliProtection, ReportThatIsTheInputOrTheOutput) {
  const auto d = with_input("report", "in.gltf");
  expect_refused("in.gltf -o out.glb --report in.gltf --quiet", d, "in.gltf", "is the input");
  expect_refused("in.gltf -o out.glb --report out.glb --quiet", d, "in.gltf", "among this run's outputs");
}

TEST(CliProtection, LodNameThatIsTheInput) {
  const auto d = with_input("lod_name", "w_lod2.gltf");
  expect_refused("w_lod2.gltf -o w.gltf --lods 0.5,0.25 --quiet", d, "w_lod2.gltf", "is the input");
}

TEST(CliProtection, HardLinkAndSymlinkToTheInput) {
  const auto d = with_input("links", "in.gltf");
  fs::create_hard_link(d / "in.gltf", d / "hard.gltf");
  fs::create_symlink(d / "in.gltf", d / "sym.gltf");
  expect_refused("in.gltf -o hard.gltf --quiet", d, "in.gltf", "is the input");
  expect_refused("in.gltf -o sym.gltf --quiet", d, "in.gltf", "is the input");
}

TEST(CliProtection, UsageErrors) {
  const auto d = with_input("usage", "in.gltf");
  expect_refused("in.gltf -o out.glb --faces 0", d, "in.gltf", "--faces must be at least 1");
  expect_refused("in.gltf -o out.glb --poses 100000", d, "in.gltf", "--poses must be 1 to");
  // In process: a 1 MB address-space limit on the isolated reader would stop the reader itself first (how
  // much a forked reader can still allocate under it depends on the parent's heap).
  expect_refused("in.gltf -o out.glb --poses 1000 --max-memory 1 --no-isolate", d, "in.gltf", "over --max-memory 1 MB");
}

TEST(CliProtection, ReaderCrashIsOneLineAndLeavesThePreviousOutput) {
  const auto d = scratch("crash");
  fs::copy_file(std::string(OMSK_TEST_DATA) + "/crashers/md5_mutant_segv_1.md5mesh", d / "bad.md5mesh");
  std::ofstream(d / "out.glb") << "previous run";
  const auto r = cli("bad.md5mesh -o out.glb --lods 0.5,0.25 --report out.json", d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(error_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("the reader crashed"), std::string::npos) << r.out;
  EXPECT_EQ(read(d / "out.glb"), "previous run");
  EXPECT_EQ(files_in(d), (std::vector<std::string>{"bad.md5mesh", "out.glb"}));
}

TEST(CliProtection, SkeletonOnlyInputIsRefused) {
  const auto d = scratch("bvh");
  const auto r = cli(std::string("'") + OMSK_TEST_MODELS + "/BVH/01_01.bvh' -o out.glb", d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(error_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("contains no mesh, only a skeleton"), std::string::npos) << r.out;
  EXPECT_TRUE(files_in(d).empty());
}

TEST(CliProtection, UnnamedRootNodesAreValidNodes) {
  // PLY and STL scenes have an unnamed root; it used to be written as a null node.
  const auto d = scratch("ply");
  for (const char* in : {"PLY/cube.ply", "STL/Spider_binary.stl"}) {
    const auto r = cli(std::string("'") + OMSK_TEST_MODELS + "/" + in + "' -o out.glb --quiet", d);
    ASSERT_EQ(r.code, 0) << r.out;
    omsk_test::expect_valid_gltf((d / "out.glb").string());
  }
}

TEST(CliProtection, AnUnreachableTargetIsStated) {
  const auto d = scratch("unreachable");
  const auto r =
      cli(std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X' -o out.glb --faces 1 --report r.json --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("target of 1 triangles not reached"), std::string::npos) << r.out;
  nlohmann::json rep = omsk_test::read_json(d / "r.json");
  EXPECT_EQ(rep["lods"][0]["target_faces"], 1);
  EXPECT_EQ(rep["lods"][0]["target_reached"], false);
  EXPECT_GT(rep["lods"][0]["faces"].get<int>(), 1);
}

TEST(CliProtection, DroppedDataIsAWarningEvenWhenQuiet) {
  const auto d = scratch("dropped");
  tinygltf::Model m = omsk_spec::load(simple_skin);
  const auto& acc = m.accessors[m.meshes[0].primitives[0].indices];
  const auto& view = m.bufferViews[acc.bufferView];
  *reinterpret_cast<uint16_t*>(m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset) = 99;
  tinygltf::TinyGLTF w;  // .gltf with the buffers inline (a GLB holds one buffer, simple_skin has four)
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, (d / "oor.gltf").string(), true, true, true, false));
  const auto r = cli("oor.gltf -o out.glb --quiet", d);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("warning: oor.gltf: the reader dropped data: Some faces had out-of-range indices"),
            std::string::npos)
      << r.out;
}

TEST(CliProtection, OutOfRangeIndexInObjIsAnError) {
  const auto d = scratch("obj_oor");
  // An OBJ face whose index is out of range: assimp refuses the file; say so in one line.
  std::ofstream(d / "oor.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 99\n";
  const auto r = cli("oor.obj -o out.glb --quiet", d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(error_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("out of range"), std::string::npos) << r.out;
}
