// STEP and CUBICSPLINE animation samplers (GltfInterpolation through GltfRepair): assimp 5.2 blends STEP keys
// and drops CUBICSPLINE tangents, so the tool rewrites them as LINEAR keys first. The files are posed by the
// independent spec poser (tinygltf), which knows all three interpolations, and must move as the input does.
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/GltfAccessors.hh>
#include <OpenMeshSkinned/IO/GltfInterpolation.hh>
#include <OpenMeshSkinned/IO/GltfRepair.hh>
#include <OpenMeshSkinned/IO/IOError.hh>

#include <gtest/gtest.h>
#include <cereal/external/base64.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;
using json = nlohmann::json;

namespace {

const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";

fs::path dir() {
  static const fs::path d = omsk_test::scratch_dir("interpolation", "fixtures");
  return d;
}

// simple_skin (one rotation sampler, 12 keys half a second apart) with its sampler made STEP, or made
// CUBICSPLINE with tangents 1.5 times the Catmull-Rom ones (so that the curve is no chord between keys).
std::string fixture(const std::string& interpolation) {
  tinygltf::Model m = omsk_spec::load(simple_skin);
  tinygltf::AnimationSampler& s = m.animations[0].samplers[0];
  s.interpolation = interpolation;
  if (interpolation == "CUBICSPLINE") {
    const std::vector<double> in = omsk_spec::read(m, s.input), out = omsk_spec::read(m, s.output);
    const size_t keys = in.size();
    std::vector<float> cubic;
    for (size_t k = 0; k < keys; ++k) {
      float tangent[4] = {0, 0, 0, 0};
      if (k > 0 && k + 1 < keys)
        for (int c = 0; c < 4; ++c)
          tangent[c] = float(1.5 * (out[4 * (k + 1) + c] - out[4 * (k - 1) + c]) / (in[k + 1] - in[k - 1]));
      cubic.insert(cubic.end(), tangent, tangent + 4);
      for (int c = 0; c < 4; ++c) cubic.push_back(float(out[4 * k + c]));
      cubic.insert(cubic.end(), tangent, tangent + 4);
    }
    tinygltf::Buffer b;
    b.data.resize(cubic.size() * sizeof(float));
    std::memcpy(b.data.data(), cubic.data(), b.data.size());
    m.buffers.push_back(b);
    tinygltf::BufferView v;
    v.buffer = int(m.buffers.size()) - 1;
    v.byteLength = b.data.size();
    m.bufferViews.push_back(v);
    tinygltf::Accessor a;
    a.bufferView = int(m.bufferViews.size()) - 1;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC4;
    a.count = 3 * keys;
    m.accessors.push_back(a);
    s.output = int(m.accessors.size()) - 1;
  }
  // As .gltf with its buffers as data URIs: assimp 5.2 cannot read a GLB whose buffers are all URIs.
  const std::string path = (dir() / (interpolation + ".gltf")).string();
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, path, true, true, true, false));
  return path;
}

// The largest distance, both ways, between two files posed by the spec at \p times of the first clip, over
// the first file's diagonal.
double worst_at(const std::string& a_path, const std::string& b_path, const std::vector<double>& times) {
  const tinygltf::Model a = omsk_spec::load(a_path), b = omsk_spec::load(b_path);
  double worst = 0.0;
  for (double t : times) {
    const auto pa = omsk_spec::pose(a, 0, t), pb = omsk_spec::pose(b, 0, t);
    worst = std::max({worst, omsk_spec::max_nearest_distance(pa, pb), omsk_spec::max_nearest_distance(pb, pa)});
  }
  return worst / omsk_spec::diagonal(omsk_spec::pose(a, -1, 0.0));
}

// Halfway between the keys (where a STEP key and a blend differ most), and at tenths (the cubic curve).
std::vector<double> midpoints() {
  std::vector<double> t;
  for (int k = 0; k < 11; ++k) t.push_back(0.25 + 0.5 * k);
  return t;
}
std::vector<double> tenths() {
  std::vector<double> t;
  for (int k = 0; k <= 55; ++k) t.push_back(0.1 * k);
  return t;
}

// A document with one sampler of \p interpolation: \p times and \p values (\p type) in one data-URI buffer.
json one_sampler(const std::string& interpolation, const std::vector<float>& times, const std::vector<float>& values,
                 const std::string& type, const std::string& path) {
  std::vector<float> all(times);
  all.insert(all.end(), values.begin(), values.end());
  const auto* p = reinterpret_cast<const unsigned char*>(all.data());
  const size_t bytes = all.size() * sizeof(float), tb = times.size() * sizeof(float);
  const size_t value_count = type == "SCALAR" ? values.size() : values.size() / detail::component_count(type);
  json doc = json::parse(R"({"asset": {"version": "2.0"}, "nodes": [{"name": "n"}],
    "bufferViews": [{"buffer": 0}, {"buffer": 0}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "SCALAR"}, {"bufferView": 1, "componentType": 5126}],
    "animations": [{"samplers": [{"input": 0, "output": 1}], "channels": [{"sampler": 0, "target": {"node": 0}}]}]})");
  doc["buffers"] = json::array(
      {{{"byteLength", bytes}, {"uri", "data:application/octet-stream;base64," + cereal::base64::encode(p, bytes)}}});
  doc["bufferViews"][0]["byteLength"] = tb;
  doc["bufferViews"][1]["byteOffset"] = tb;
  doc["bufferViews"][1]["byteLength"] = bytes - tb;
  doc["accessors"][0]["count"] = times.size();
  doc["accessors"][1]["count"] = value_count;
  doc["accessors"][1]["type"] = type;
  doc["animations"][0]["samplers"][0]["interpolation"] = interpolation;
  doc["animations"][0]["channels"][0]["target"]["path"] = path;
  return doc;
}

std::vector<double> values_of(json& doc, const char* which, detail::GltfBytes& bytes) {
  return detail::accessor_values(doc, doc["animations"][0]["samplers"][0][which].get<size_t>(), bytes, "t");
}

}  // namespace

TEST(GltfInterpolation, StepKeysSwitchWithinAMillisecondBeforeEachKey) {
  json doc = one_sampler("STEP", {0.0f, 1.0f, 1.0015f}, {0, 0, 0, 5, 0, 0, 7, 0, 0}, "VEC3", "translation");
  detail::GltfBytes bytes(doc, nullptr, dir(), "t");
  const auto notes = detail::linearize_samplers(doc, bytes, "t");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("1 STEP animation sampler kept as LINEAR keys"), std::string::npos) << notes[0];
  EXPECT_EQ(doc["animations"][0]["samplers"][0]["interpolation"], "LINEAR");
  const std::vector<double> t = values_of(doc, "input", bytes), v = values_of(doc, "output", bytes);
  // 1 ms before the second key; half the 1.5 ms gap before the third.
  ASSERT_EQ(t.size(), 5u);
  EXPECT_NEAR(t[1], 0.999, 1e-6);
  EXPECT_NEAR(t[3], 1.00075, 1e-6);
  const std::vector<double> x = {v[0], v[3], v[6], v[9], v[12]};
  EXPECT_EQ(x, (std::vector<double>{0, 0, 5, 5, 7}));
  const json& input = doc["accessors"][doc["animations"][0]["samplers"][0]["input"].get<size_t>()];
  EXPECT_NEAR(input["max"][0].get<double>(), 1.0015, 1e-6);  // the spec requires an input's bounds
}

TEST(GltfInterpolation, CubicKeysFollowTheHermiteCurveAndRotationsStayUnit) {
  // Two keys one second apart; rotation about z from identity to 90 degrees, with strong tangents that
  // differ at the two ends (an out-tangent used for the in-tangent would show).
  const float s = std::sqrt(0.5f);
  json doc = one_sampler("CUBICSPLINE", {0.0f, 1.0f}, {0,        0, 0, 0, /*v0*/ 0, 0, 0, 1, /*b0*/ 0, 0, 2, 0,
                                                       /*a1*/ 0, 0, 1, 0, /*v1*/ 0, 0, s, s, 0,        0, 0, 0},
                         "VEC4", "rotation");
  detail::GltfBytes bytes(doc, nullptr, dir(), "t");
  ASSERT_EQ(detail::linearize_samplers(doc, bytes, "t").size(), 1u);
  const std::vector<double> t = values_of(doc, "input", bytes), v = values_of(doc, "output", bytes);
  ASSERT_EQ(t.size(), size_t(detail::kCubicSegments + 1));
  EXPECT_DOUBLE_EQ(t.back(), 1.0);
  for (size_t k = 0; k < t.size(); ++k) {
    const double u = t[k], u2 = u * u, u3 = u2 * u;
    const double z = (u3 - 2 * u2 + u) * 2 + (-2 * u3 + 3 * u2) * s + (u3 - u2) * 1,
                 w = (2 * u3 - 3 * u2 + 1) * 1 + (-2 * u3 + 3 * u2) * s;
    const double len = std::hypot(z, w);
    EXPECT_NEAR(v[4 * k + 2], z / len, 1e-6) << "u " << u;
    EXPECT_NEAR(v[4 * k + 3], w / len, 1e-6) << "u " << u;
  }
}

TEST(GltfInterpolation, AnOutputThatDoesNotFitItsKeysIsRefused) {
  json doc = one_sampler("CUBICSPLINE", {0.0f, 1.0f}, {0, 1, 2, 3, 4}, "SCALAR", "weights");
  detail::GltfBytes bytes(doc, nullptr, dir(), "bad.gltf");
  try {
    detail::linearize_samplers(doc, bytes, "bad.gltf");
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_NE(
        std::string(e.what()).find("bad.gltf: animation 0 sampler 0 (CUBICSPLINE) has 5 output values for 2 keys"),
        std::string::npos)
        << e.what();
  }
}

TEST(GltfInterpolation, LinearSamplersNeedNoCopy) { EXPECT_TRUE(RepairedGltf(simple_skin).path().empty()); }

TEST(GltfInterpolation, TheRepairedCopyPosesLikeTheInput) {
  for (const std::string kind : {"STEP", "CUBICSPLINE"}) {
    const std::string in = fixture(kind);
    // The fixture must be unlike its LINEAR original, or the comparisons below could not fail.
    EXPECT_GT(worst_at(in, simple_skin, kind == "STEP" ? midpoints() : tenths()), 0.01) << kind;
    const RepairedGltf copy(in);
    ASSERT_FALSE(copy.path().empty()) << kind;
    ASSERT_EQ(copy.notes().size(), 1u) << kind;
    EXPECT_NE(copy.notes()[0].find(kind + " animation sampler kept as LINEAR keys"), std::string::npos)
        << copy.notes()[0];
    const tinygltf::Model m = omsk_spec::load(copy.path());
    for (const auto& s : m.animations[0].samplers) EXPECT_EQ(s.interpolation, "LINEAR") << kind;
    EXPECT_LT(worst_at(in, copy.path(), kind == "STEP" ? midpoints() : tenths()), kind == "STEP" ? 1e-6 : 2e-3) << kind;
    omsk_test::expect_valid_gltf(copy.path());
  }
}

TEST(GltfInterpolation, TheToolsLodMovesLikeTheInputAndSaysWhatItKept) {
  for (const std::string kind : {"STEP", "CUBICSPLINE"}) {
    const std::string in = fixture(kind);
    const fs::path d = omsk_test::scratch_dir("interpolation", kind);
    const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + in + "' -o out.glb --ratio 1", d);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(kind + " animation sampler kept as LINEAR keys"), std::string::npos) << r.out;
    EXPECT_LT(worst_at(in, (d / "out.glb").string(), kind == "STEP" ? midpoints() : tenths()),
              kind == "STEP" ? 1e-4 : 2e-3)
        << kind;
    omsk_test::expect_valid_gltf((d / "out.glb").string());
  }
}

// A file the repair must copy (its STEP sampler) whose image is named by an absolute Windows path: the
// copy cannot link it, and needs not (materials read images beside the input), so the image still arrives.
TEST(GltfInterpolation, ARepairedCopyKeepsAnImageNamedOutsideItsFolder) {
  const fs::path d = omsk_test::scratch_dir("interpolation", "outside_image");
  tinygltf::Model m = omsk_spec::load(simple_skin);
  m.animations[0].samplers[0].interpolation = "STEP";
  tinygltf::Image img;
  img.uri = "C:/art/skin.png";
  m.images.push_back(img);
  tinygltf::Texture tex;
  tex.source = 0;
  m.textures.push_back(tex);
  tinygltf::Material mat;
  mat.name = "skin";
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  m.materials.push_back(mat);
  m.meshes[0].primitives[0].material = 0;
  const std::string in = (d / "outside.gltf").string();
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&m, in, false, true, true, false));
  fs::copy_file(std::string(OMSK_TEST_MODELS) + "/glTF2/BoxTextured-glTF/CesiumLogoFlat.png", d / "skin.png");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "outside.gltf -o out.glb --ratio 1", d);
  ASSERT_EQ(r.code, 0) << r.out;
  const tinygltf::Model out = omsk_spec::load((d / "out.glb").string());
  ASSERT_EQ(out.images.size(), 1u) << r.out;
  EXPECT_EQ(out.images[0].mimeType, "image/png");
}

// A weights channel holds one value per morph target and key: two targets, cubic, as SCALAR outputs.
TEST(GltfInterpolation, CubicMorphWeightsKeepOneValuePerTarget) {
  // Per key: in-tangents (2), values (2), out-tangents (2); the second target runs backwards.
  json doc =
      one_sampler("CUBICSPLINE", {0.0f, 2.0f}, {0, 0, 0, 1, 0.5f, -0.5f, 0.5f, -0.5f, 1, 0, 0, 0}, "SCALAR", "weights");
  detail::GltfBytes bytes(doc, nullptr, dir(), "t");
  ASSERT_EQ(detail::linearize_samplers(doc, bytes, "t").size(), 1u);
  const std::vector<double> t = values_of(doc, "input", bytes), v = values_of(doc, "output", bytes);
  ASSERT_EQ(t.size(), size_t(detail::kCubicSegments + 1));
  ASSERT_EQ(v.size(), 2 * t.size());
  const json& out = doc["accessors"][doc["animations"][0]["samplers"][0]["output"].get<size_t>()];
  EXPECT_EQ(out["type"], "SCALAR");
  EXPECT_EQ(out["count"].get<size_t>(), v.size());
  for (size_t k = 0; k < t.size(); ++k) {
    const double u = t[k] / 2.0, u2 = u * u, u3 = u2 * u, dt = 2.0;
    // Target 0: from 0 to 1 with tangents 0.5 and 0.5; target 1: from 1 to 0 with tangents -0.5 and -0.5.
    const double w0 = (u3 - 2 * u2 + u) * dt * 0.5 + (-2 * u3 + 3 * u2) * 1 + (u3 - u2) * dt * 0.5;
    const double w1 = (2 * u3 - 3 * u2 + 1) * 1 + (u3 - 2 * u2 + u) * dt * -0.5 + (u3 - u2) * dt * -0.5;
    EXPECT_NEAR(v[2 * k], w0, 1e-6) << "u " << u;
    EXPECT_NEAR(v[2 * k + 1], w1, 1e-6) << "u " << u;
  }
}

// Keys one float apart (how some exporters fake a step) leave no room for steps between them: the written
// times still increase strictly, as the spec requires.
TEST(GltfInterpolation, CubicKeysOneFloatApartKeepTheTimesIncreasing) {
  const float t1 = std::nextafter(10.0f, 20.0f);
  json doc = one_sampler("CUBICSPLINE", {10.0f, t1, 11.0f}, {0, 0, 0, 0, 1, 0, 0, 2, 0}, "SCALAR", "weights");
  detail::GltfBytes bytes(doc, nullptr, dir(), "t");
  ASSERT_EQ(detail::linearize_samplers(doc, bytes, "t").size(), 1u);
  const std::vector<double> t = values_of(doc, "input", bytes);
  ASSERT_EQ(t.size(), size_t(2 + detail::kCubicSegments));  // the two keys, then the second interval's steps
  for (size_t k = 1; k < t.size(); ++k) EXPECT_LT(float(t[k - 1]), float(t[k])) << k;
  EXPECT_EQ(float(t.back()), 11.0f);
}

// A NaN key is one line in the file's own key numbers (the rewritten keys are numbered otherwise).
TEST(GltfInterpolation, ANonFiniteKeyIsNamedAsTheFileNumbersIt) {
  json doc = one_sampler("STEP", {0.0f, 1.0f, NAN, 3.0f}, {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3}, "VEC3", "translation");
  detail::GltfBytes bytes(doc, nullptr, dir(), "nan.gltf");
  try {
    detail::linearize_samplers(doc, bytes, "nan.gltf");
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("nan.gltf: animation 0 sampler 0 (STEP): key 2 has the time nan"),
              std::string::npos)
        << e.what();
  }
  json inf = one_sampler("CUBICSPLINE", {0.0f, 1.0f}, {0, 0, 0, 0, INFINITY, 0}, "SCALAR", "weights");
  detail::GltfBytes inf_bytes(inf, nullptr, dir(), "inf.gltf");
  EXPECT_THROW(detail::linearize_samplers(inf, inf_bytes, "inf.gltf"), IOError);
}
