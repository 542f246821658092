// Compressed glTF (GltfDecompress through GltfRepair): files packed by the pinned gltfpack (meshopt, with
// and without quantisation) and by Debian's draco_transcoder read like the originals they were made from,
// and the tool judges them lossless at --ratio 1. The decoded copy is checked on its own with the
// independent spec poser (tinygltf, which knows none of these extensions).
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/GltfRepair.hh>
#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <set>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;
using json = nlohmann::json;

namespace {

const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";
const std::string engine = std::string(OMSK_TEST_MODELS) + "/glTF2/draco/2CylinderEngine.gltf";
const std::string gltfpack = (fs::path(OMSK_VALIDATOR).parent_path() / "node_modules/gltfpack/cli.js").string();

fs::path dir() {
  static const fs::path d = omsk_test::scratch_dir("compressed", "fixtures");
  return d;
}

void run(const std::string& cmd) {
  const auto r = omsk_test::run_command("/bin/sh", "-c \"" + cmd + "\"", dir());
  ASSERT_EQ(r.code, 0) << cmd << ":\n" << r.out << "(scripts/setup installs gltfpack and draco_transcoder)";
}

// The originals: Testwuson (40 joints, three clips, one textured primitive) as the tool writes it, and
// Debian's simple_skin. Each compressed fixture names the original it was made from.
struct Fixture {
  std::string file, original;
  bool quantized, draco;
};

const std::map<std::string, Fixture>& fixtures() {
  static const std::map<std::string, Fixture> all = [] {
    std::map<std::string, Fixture> f;
    const std::string wuson = (dir() / "wuson.glb").string();
    SkinnedMesh mesh;
    import_skinned(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", mesh);
    export_gltf(mesh, wuson);
    for (const auto& [name, src] :
         {std::pair<std::string, std::string>{"wuson", wuson}, {"simple_skin", simple_skin}}) {
      for (const auto& [suffix, flags] : std::map<std::string, std::string>{
               {"c", "-c"}, {"cc", "-cc"}, {"c_noq", "-c -noq"}, {"cc_noq", "-cc -noq"}}) {
        const std::string out = name + "_" + suffix + ".glb";
        run("node '" + gltfpack + "' -i '" + src + "' -o " + out + " " + flags);
        f[name + "_" + suffix] = {(dir() / out).string(), src, suffix.find("noq") == std::string::npos, false};
      }
      // As .gltf beside its .bin, the fallback buffer is a buffer of its own, dropped after decoding.
      run("node '" + gltfpack + "' -i '" + src + "' -o " + name + "_c_text.gltf -c");
      f[name + "_c_text"] = {(dir() / (name + "_c_text.gltf")).string(), src, true, false};
      run("draco_transcoder -i '" + src + "' -o " + name + "_draco.glb");
      f[name + "_draco"] = {(dir() / (name + "_draco.glb")).string(), src, true, true};
    }
    // A large scene: 34 Draco primitives in 29 meshes, instanced by 67 nodes.
    const std::string engine_glb =
        std::string(OMSK_TEST_MODELS) + "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    run("draco_transcoder -i '" + engine_glb + "' -o engine_draco.glb");
    f["engine_draco"] = {(dir() / "engine_draco.glb").string(), engine_glb, true, true};
    return f;
  }();
  return all;
}

std::set<std::string> joint_names(const SkinnedMesh& mesh) {
  std::set<std::string> names;
  for (const auto& j : skeleton(mesh).joints) names.insert(j.name);
  return names;
}

double diagonal_of(const tinygltf::Model& m) { return omsk_spec::diagonal(omsk_spec::pose(m, -1, 0.0)); }

// The largest distance, both ways, between two files posed by the spec, over the first one's diagonal: at
// the rest pose, or at eight times of every clip (clips matched by position).
double worst_posed_distance(const tinygltf::Model& a, const tinygltf::Model& b, bool animated) {
  double worst = 0.0;
  auto compare = [&](int anim, double t) {
    const auto pa = omsk_spec::pose(a, anim, t), pb = omsk_spec::pose(b, anim, t);
    worst = std::max({worst, omsk_spec::max_nearest_distance(pa, pb), omsk_spec::max_nearest_distance(pb, pa)});
  };
  if (!animated) compare(-1, 0.0);
  for (size_t anim = 0; animated && anim < a.animations.size(); ++anim)
    for (int k = 0; k <= 7; ++k) compare(int(anim), omsk_spec::duration(a, int(anim)) * k / 7.0);
  return worst / diagonal_of(a);
}

// At rest, gltfpack's 14-bit positions move a vertex by less than 2^-14 of the box on each axis, Draco's
// 11-bit ones by less than 2^-11; without quantisation nothing moves. Draco also stores the weights in 8
// bits, so their sums are off by up to 0.4% until the importer rescales them (\p raw_weights: not yet).
// Posed, gltfpack resamples every clip at 30 Hz and stores rotations in 16 bits even with -noq.
void expect_poses_alike(const Fixture& f, const tinygltf::Model& original, const tinygltf::Model& other,
                        const std::string& what, bool raw_weights) {
  const double rest = worst_posed_distance(original, other, false),
               moving = worst_posed_distance(original, other, true);
  std::cout << what << ": rest " << rest << ", animated " << moving << " of the diagonal\n";
  const double step = !f.quantized ? 1e-6 : f.draco ? (raw_weights ? 3e-3 : 1e-3) : 2e-4;
  EXPECT_LT(rest, step) << what;
  EXPECT_LT(moving, step + 1e-3) << what;
}

class Compressed : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(Compressed, DecodedCopyPosesLikeTheOriginal) {
  const Fixture& f = fixtures().at(GetParam());
  const RepairedGltf copy(f.file);
  ASSERT_FALSE(copy.path().empty()) << "a compressed file needs a decoded copy";
  const tinygltf::Model decoded = omsk_spec::load(copy.path()), original = omsk_spec::load(f.original);
  for (const char* ext : {"EXT_meshopt_compression", "KHR_draco_mesh_compression", "KHR_mesh_quantization"}) {
    EXPECT_EQ(std::count(decoded.extensionsUsed.begin(), decoded.extensionsUsed.end(), ext), 0) << ext;
    EXPECT_EQ(std::count(decoded.extensionsRequired.begin(), decoded.extensionsRequired.end(), ext), 0) << ext;
  }
  ASSERT_EQ(decoded.animations.size(), original.animations.size());
  for (size_t a = 0; a < original.animations.size(); ++a)
    EXPECT_NEAR(omsk_spec::duration(decoded, int(a)), omsk_spec::duration(original, int(a)), 1e-3);
  expect_poses_alike(f, original, decoded, GetParam() + " decoded", true);
  // Draco's 8-bit weights do not sum to 1 closely enough for the validator; meshopt is lossless.
  if (!f.draco) omsk_test::expect_valid_gltf(copy.path());
}

TEST_P(Compressed, ImportsLikeTheOriginal) {
  const Fixture& f = fixtures().at(GetParam());
  SkinnedMesh packed, plain;
  ImportReport rp, ro;
  ASSERT_NO_THROW(rp = import_skinned(f.file, packed));
  ro = import_skinned(f.original, plain);
  // The importer skips degenerate triangles (a repeated vertex). Draco's encoder drops them itself, and its
  // 11-bit positions make a few slivers degenerate (the engine: 10 of 110,336).
  if (f.draco) {
    EXPECT_LE(rp.faces, ro.faces);
    EXPECT_GE(rp.faces, ro.faces - ro.faces / 1000);
  } else {
    EXPECT_EQ(rp.faces, ro.faces);
  }
  EXPECT_EQ(rp.rigid, ro.rigid);
  // gltfpack re-indexes the vertices (Testwuson: 2,164 welded against 2,173 with -noq); quantisation may
  // also weld vertices that were apart by less than a step.
  EXPECT_NEAR(double(rp.welded_vertices), double(ro.welded_vertices), (f.quantized ? 0.1 : 0.01) * ro.welded_vertices);
  const std::set<std::string> packed_joints = joint_names(packed);
  for (const std::string& j : joint_names(plain))
    // assimp names its own helper nodes "$…" and unnamed nodes by their index ("nodes[3]"), which a packer
    // may renumber: only the file's names must survive.
    if (!j.empty() && j.rfind("$", 0) != 0 && j.rfind("nodes[", 0) != 0) {
      EXPECT_TRUE(packed_joints.count(j)) << "joint " << j << " is lost";
    }
  ASSERT_EQ(clips(packed).size(), clips(plain).size());
  for (size_t c = 0; c < clips(plain).size(); ++c) {
    EXPECT_EQ(clips(packed)[c].name, clips(plain)[c].name);
    EXPECT_NEAR(clips(packed)[c].duration, clips(plain)[c].duration, 1e-3);
  }
  // Posed as the spec poses what the importer made of each, they agree within the quantisation.
  const fs::path out = dir() / (GetParam() + "_imported.glb");
  export_gltf(packed, out.string());
  expect_poses_alike(f, omsk_spec::load(f.original), omsk_spec::load(out.string()), GetParam() + " imported", false);
}

TEST_P(Compressed, RatioOneIsJudgedLosslessAndValid) {
  const Fixture& f = fixtures().at(GetParam());
  const fs::path d = omsk_test::scratch_dir("compressed", GetParam());
  const auto r =
      omsk_test::run_command(OMSK_CLI_EXE, "'" + f.file + "' -o out.glb --ratio 1 --quiet --report r.json", d);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("unsupported"), std::string::npos) << r.out;
  const json rep = omsk_test::read_json(d / "r.json");
  const json& lod = rep["lods"][0];
  EXPECT_LT(lod["heldout_rms"].get<double>(), 1e-5) << r.out;
  EXPECT_LT(lod["heldout_hausdorff"].get<double>(), 1e-5) << r.out;
  omsk_test::expect_valid_gltf((d / "out.glb").string());
}

INSTANTIATE_TEST_SUITE_P(Packed, Compressed,
                         ::testing::Values("wuson_c", "wuson_cc", "wuson_c_noq", "wuson_cc_noq", "wuson_c_text",
                                           "wuson_draco", "simple_skin_c", "simple_skin_cc", "simple_skin_c_noq",
                                           "simple_skin_cc_noq", "simple_skin_c_text", "simple_skin_draco",
                                           "engine_draco"));

// Debian's Draco sample: 34 Draco primitives in 29 meshes, every one decoded by the tool before assimp
// reads the file; every triangle the file's accessors declare arrives.
TEST(CompressedGltf, DracoSceneWithManyPrimitives) {
  const RepairedGltf copy(engine);
  ASSERT_FALSE(copy.path().empty());
  const tinygltf::Model decoded = omsk_spec::load(copy.path());
  EXPECT_TRUE(decoded.extensionsRequired.empty());
  std::ifstream in(engine);
  const json doc = json::parse(in);
  // Meshes are instanced by several nodes: the importer gets each instance's triangles.
  size_t declared = 0, instanced = 0;
  std::vector<size_t> mesh_indices;
  for (const auto& m : doc["meshes"]) {
    size_t n = 0;
    for (const auto& p : m["primitives"]) n += doc["accessors"][p["indices"].get<size_t>()]["count"].get<size_t>();
    mesh_indices.push_back(n);
    declared += n;
  }
  for (const auto& node : doc["nodes"])
    if (node.contains("mesh")) instanced += mesh_indices.at(node["mesh"].get<size_t>());
  size_t decoded_indices = 0;
  for (const auto& m : decoded.meshes)
    for (const auto& p : m.primitives) decoded_indices += decoded.accessors[p.indices].count;
  EXPECT_EQ(decoded_indices, declared);
  SkinnedMesh mesh;
  const ImportReport rep = import_skinned(engine, mesh);
  EXPECT_EQ(rep.faces + rep.degenerate_faces_skipped, instanced / 3);
  omsk_test::expect_valid_gltf(copy.path());
}

// gltfpack -cz writes meshopt vertex codec version 1, which Debian's meshoptimizer 0.18 cannot decode:
// one line that names it, exit 1.
TEST(CompressedGltf, NewerMeshoptCodecIsRefusedByName) {
  const fs::path d = omsk_test::scratch_dir("compressed", "cz");
  run("node '" + gltfpack + "' -i '" + simple_skin + "' -o '" + (d / "cz.glb").string() + "' -cz");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "cz.glb -o out.glb --ratio 1 --quiet", d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("meshopt vertex codec version 1"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_FALSE(fs::exists(d / "out.glb"));
}

// Writes simple_skin with extra top-level JSON members (its buffers are data URIs).
static fs::path simple_skin_with(const fs::path& d, const std::string& name, const json& extra) {
  std::ifstream in(simple_skin);
  json doc = json::parse(in);
  for (const auto& [k, v] : extra.items()) doc[k] = v;
  const fs::path out = d / name;
  std::ofstream(out) << doc.dump();
  return out;
}

TEST(CompressedGltf, OtherRequiredExtensionIsRefusedByName) {
  const fs::path d = omsk_test::scratch_dir("compressed", "required");
  simple_skin_with(
      d, "inst.gltf",
      {{"extensionsUsed", {"EXT_mesh_gpu_instancing"}}, {"extensionsRequired", {"EXT_mesh_gpu_instancing"}}});
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "inst.gltf -o out.glb --ratio 1 --quiet", d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("requires the glTF extension EXT_mesh_gpu_instancing"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  SkinnedMesh mesh;
  EXPECT_THROW(import_skinned((d / "inst.gltf").string(), mesh), IOError);
}

// KTX2 images (KHR_texture_basisu) pass through: a file that requires the extension is read.
TEST(CompressedGltf, BasisuTexturesDoNotStopReading) {
  const fs::path d = omsk_test::scratch_dir("compressed", "basisu");
  std::ifstream in(simple_skin);
  json doc = json::parse(in);
  doc["extensionsUsed"] = doc["extensionsRequired"] = {"KHR_texture_basisu"};
  doc["images"] = {{{"uri", "skin.ktx2"}, {"mimeType", "image/ktx2"}}};
  doc["textures"] = {{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}};
  doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  for (auto& m : doc["meshes"])
    for (auto& p : m["primitives"]) p["material"] = 0;
  std::ofstream(d / "basisu.gltf") << doc.dump();
  const char ktx2_identifier[] = "\xABKTX 20\xBB\r\n\x1A\n";
  std::ofstream(d / "skin.ktx2", std::ios::binary).write(ktx2_identifier, 12);
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "basisu.gltf -o out.glb --ratio 1 --quiet", d);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("KHR_texture_basisu"), std::string::npos) << r.out;
  omsk_test::expect_valid_gltf((d / "out.glb").string());
}

// gltfpack stores UVs as 16-bit integers and undoes that with a KHR_texture_transform on every texture of
// the material, which assimp drops: the decoded copy folds it into the coordinates, so every corner keeps
// its UV (within a quantisation step) and the transform is gone.
TEST(CompressedGltf, QuantisedUvsKeepTheirCoordinates) {
  const std::string box = std::string(OMSK_TEST_MODELS) + "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
  run("node '" + gltfpack + "' -i '" + box + "' -o box_c.glb -c");
  const RepairedGltf copy((dir() / "box_c.glb").string());
  ASSERT_FALSE(copy.path().empty());
  const tinygltf::Model decoded = omsk_spec::load(copy.path()), original = omsk_spec::load(box);
  EXPECT_EQ(std::count(decoded.extensionsUsed.begin(), decoded.extensionsUsed.end(), "KHR_texture_transform"), 0);
  const auto a = omsk_spec::pose(original, -1, 0.0), b = omsk_spec::pose(decoded, -1, 0.0);
  ASSERT_TRUE(a.has_uv && b.has_uv);
  ASSERT_EQ(a.points.size(), b.points.size());
  const double diag = omsk_spec::diagonal(a);
  double uv_range = 0.0;
  for (const auto& uv : a.uvs) uv_range = std::max(uv_range, uv.cwiseAbs().maxCoeff());
  for (size_t i = 0; i < b.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < a.points.size(); ++j)
      if ((a.points[j] - b.points[i]).norm() < 1e-3 * diag) best = std::min(best, (a.uvs[j] - b.uvs[i]).norm());
    EXPECT_LT(best, 2.0 * uv_range / 4095) << "corner " << i << " (12-bit UVs)";
  }
  omsk_test::expect_valid_gltf(copy.path());
}

namespace {
// A GLB's JSON chunk edited, its binary chunk kept.
void edit_glb(const std::string& in, const std::string& out, const std::function<void(json&)>& edit) {
  std::ifstream f(in, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  uint32_t json_len = 0;
  std::memcpy(&json_len, data.data() + 12, 4);
  json doc = json::parse(data.substr(20, json_len));
  edit(doc);
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  const std::string rest = data.substr(20 + json_len);
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::ofstream(out, std::ios::binary) << "glTF" << u32(2) << u32(uint32_t(20 + text.size() + rest.size()))
                                       << u32(uint32_t(text.size())) << "JSON" << text << rest;
}

}  // namespace

// Truncated compressed streams: one line naming the part that cannot be decoded, exit 1, no output.
TEST(CompressedGltf, CorruptStreamsAreOneLine) {
  const fs::path d = omsk_test::scratch_dir("compressed", "corrupt");
  edit_glb(fixtures().at("simple_skin_c").file, (d / "meshopt.glb").string(), [](json& doc) {
    auto& e = doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    e["byteLength"] = e["byteLength"].get<size_t>() / 2;
  });
  edit_glb(fixtures().at("wuson_draco").file, (d / "draco.glb").string(), [](json& doc) {
    const size_t v = doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
    doc["bufferViews"][v]["byteLength"] = doc["bufferViews"][v]["byteLength"].get<size_t>() / 2;
  });
  for (const auto& [file, says] : {std::pair<std::string, std::string>{"meshopt.glb", "buffer view 0"},
                                   {"draco.glb", "primitive 0 of mesh 0: its Draco data cannot be decoded"}}) {
    const auto r = omsk_test::run_command(OMSK_CLI_EXE, file + " -o out.glb --ratio 1 --quiet", d);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find(says), std::string::npos) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_FALSE(fs::exists(d / "out.glb"));
  }
}
