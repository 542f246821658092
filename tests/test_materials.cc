// What a viewer shows survives: every material of a glTF input comes out as the file has it (factors,
// texture references with texCoord, transform and sampler, alpha, doubleSided, extras, KHR_materials_*
// extensions, images byte for byte, KTX2 included), faces keep their material, and other formats' materials
// are mapped to glTF PBR (FBX metal/rough maps and factors, opacity, emissive, Collada two-sided).
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/GltfMaterials.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/Textures.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>
#include <cereal/external/base64.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using json = nlohmann::json;
using uchar = unsigned char;
using namespace OpenMeshSkinned;

namespace {

fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("materials", name); }
std::string models(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A written or input glTF: its JSON, a GLB's binary chunk, and where its files are.
struct Doc {
  json j;
  std::string bin;
  fs::path dir;
};

Doc load(const fs::path& path) {
  Doc d;
  d.dir = path.parent_path();
  const std::string data = read_file(path);
  if (data.compare(0, 4, "glTF") == 0) {
    uint32_t len = 0, bin_len = 0;
    std::memcpy(&len, data.data() + 12, 4);
    d.j = json::parse(data.substr(20, len));
    if (data.size() > 28 + len) {
      std::memcpy(&bin_len, data.data() + 20 + len, 4);
      d.bin = data.substr(28 + len, bin_len);
    }
  } else {
    d.j = json::parse(data);
  }
  return d;
}

std::string uri_bytes(const Doc& d, const std::string& uri) {
  if (uri.rfind("data:", 0) == 0) return cereal::base64::decode(uri.substr(uri.find(',') + 1));
  std::string path;  // glTF URIs are percent-encoded
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size()) {
      path += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      path += uri[i];
    }
  }
  return read_file(d.dir / path);
}

std::string image_bytes(const Doc& d, int i) {
  const json& img = d.j["images"][i];
  if (img.contains("uri")) return uri_bytes(d, img["uri"]);
  const json& view = d.j["bufferViews"][img["bufferView"].get<int>()];
  const json& buf = d.j["buffers"][view["buffer"].get<int>()];
  const std::string all = buf.contains("uri") ? uri_bytes(d, buf["uri"]) : d.bin;
  return all.substr(view.value("byteOffset", 0), view["byteLength"].get<size_t>());
}

// A texture as what it shows: its object with the sampler written out (defaults filled) and every image
// ("source", and the sources inside extensions) replaced by its bytes' size and hash.
json resolved_texture(const Doc& d, int t) {
  json tex = d.j["textures"][t];
  json sampler = tex.contains("sampler") ? d.j["samplers"][tex["sampler"].get<int>()] : json::object();
  if (!sampler.contains("wrapS")) sampler["wrapS"] = 10497;
  if (!sampler.contains("wrapT")) sampler["wrapT"] = 10497;
  tex["sampler"] = sampler;
  auto image = [&](json& src) {
    const std::string bytes = image_bytes(d, src.get<int>());
    src = {{"size", bytes.size()}, {"hash", std::hash<std::string>()(bytes)}};
  };
  if (tex.contains("source")) image(tex["source"]);
  if (tex.contains("extensions"))
    for (auto& [name, ext] : tex["extensions"].items())
      if (ext.contains("source")) image(ext["source"]);
  return tex;
}

// A material as a viewer reads it: glTF's defaults filled in, texture references resolved.
json resolved_material(const Doc& d, int m) {
  json mat = d.j["materials"][m];
  std::function<void(json&)> walk = [&](json& node) {
    if (!node.is_object()) return;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string& k = it.key();
      if (k == "extras") continue;
      if (k.size() > 7 && k.compare(k.size() - 7, 7, "Texture") == 0 && it->contains("index")) {
        (*it)["index"] = resolved_texture(d, (*it)["index"].get<int>());
        if (!it->contains("texCoord")) (*it)["texCoord"] = 0;
        if (k == "normalTexture" && !it->contains("scale")) (*it)["scale"] = 1.0;
        if (k == "occlusionTexture" && !it->contains("strength")) (*it)["strength"] = 1.0;
      }
      walk(*it);
    }
  };
  walk(mat);
  json& pbr = mat["pbrMetallicRoughness"];
  if (!pbr.contains("baseColorFactor")) pbr["baseColorFactor"] = {1, 1, 1, 1};
  if (!pbr.contains("metallicFactor")) pbr["metallicFactor"] = 1;
  if (!pbr.contains("roughnessFactor")) pbr["roughnessFactor"] = 1;
  if (!mat.contains("emissiveFactor")) mat["emissiveFactor"] = {0, 0, 0};
  if (!mat.contains("alphaMode")) mat["alphaMode"] = "OPAQUE";
  if (!mat.contains("alphaCutoff")) mat["alphaCutoff"] = 0.5;
  if (!mat.contains("doubleSided")) mat["doubleSided"] = false;
  return mat;
}

// Every material the input's meshes use is in the output, field by field (the output may add glTF's
// default material for faces that had none, and shares identical textures).
void expect_same_materials(const fs::path& input, const fs::path& output) {
  const Doc in = load(input), out = load(output);
  std::map<std::string, int> by_name;
  for (size_t m = 0; m < out.j["materials"].size(); ++m) by_name[out.j["materials"][m].value("name", "")] = int(m);
  for (size_t m = 0; m < in.j["materials"].size(); ++m) {
    const std::string name = in.j["materials"][m].value("name", "");
    ASSERT_TRUE(by_name.count(name)) << "material \"" << name << "\" missing from " << output;
    EXPECT_EQ(resolved_material(out, by_name[name]), resolved_material(in, int(m))) << "material \"" << name << "\"";
  }
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    const json none = json::array();
    for (const json& e : in.j.value(key, none)) {
      const json outs = out.j.value(key, none);
      EXPECT_NE(std::find(outs.begin(), outs.end(), e), outs.end()) << e << " missing from the output's " << key;
    }
  }
}

// Triangles per material name over every mesh instance of a glTF (what each material covers).
std::map<std::string, size_t> triangles_per_material(const fs::path& file) {
  const Doc d = load(file);
  std::map<std::string, size_t> n;
  for (const json& node : d.j["nodes"]) {
    if (!node.contains("mesh")) continue;
    for (const json& p : d.j["meshes"][node["mesh"].get<int>()]["primitives"]) {
      const std::string name =
          p.contains("material") ? d.j["materials"][p["material"].get<int>()].value("name", "") : "";
      n[name] += d.j["accessors"][p["indices"].get<int>()]["count"].get<size_t>() / 3;
    }
  }
  return n;
}

bool said(const std::vector<std::string>& warnings, const std::string& what) {
  for (const auto& w : warnings)
    if (w.find(what) != std::string::npos) return true;
  return false;
}

void lod_of(const std::string& input, const fs::path& out, const std::string& args = "--ratio 0.5") {
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + input + "' -o '" + out.string() + "' " + args + " --quiet",
                                        out.parent_path());
  ASSERT_EQ(r.code, 0) << r.out;
}

// The validator's error codes for a file.
std::vector<std::string> validator_errors(const std::string& file) {
  const auto r = omsk_test::run_validator(file);
  std::vector<std::string> codes;
  std::regex line("^\\s*error ([A-Z_0-9]+)");
  std::istringstream in(r.output);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, line)) codes.push_back(m[1]);
  }
  if (codes.empty()) {
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  return codes;
}

void write_png(const fs::path& p, int w, int h, const std::function<std::array<unsigned char, 4>(int, int)>& f) {
  std::vector<unsigned char> px(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto c = f(x, y);
      std::copy(c.begin(), c.end(), px.begin() + 4 * (size_t(y) * w + x));
    }
  Image img;
  ASSERT_TRUE(encode_rgba_png(px.data(), w, h, p.filename().string(), img));
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(img.data.data()), img.data.size());
}

// A 4x4 UASTC KTX2 file (header, one-sample data format descriptor, one level of one block).
std::string tiny_ktx2() {
  const char* hex =
      "ab4b5458203230bb0d0a1a0a000000000100000004000000040000000000000000000000010000000100000000000000680000002c0000"
      "00000000000000000000000000000000000000000000000000a00000000000000010000000000000001000000000000000"
      "2c0000000000000002002800a601020003030000100000000000000000007f000000000000000000ffffffff0000000000000000000000"
      "0000000000000000000000000000000000";
  std::string out;
  for (size_t i = 0; hex[i] && hex[i + 1]; i += 2) out += char(std::stoi(std::string(hex + i, 2), nullptr, 16));
  return out;
}

// glTF2/simple_skin (skinned, animated) given UVs and one material with every kind of field: normal
// (scaled, transformed), occlusion and metallic-roughness sharing one texture, emissive from a KTX2 image
// (KHR_texture_basisu, required), base colour with a nearest/clamp sampler, doubleSided, MASK with a
// cutoff, KHR_materials_specular (with a texture) and KHR_materials_ior, extras.
fs::path pbr_skin(const fs::path& dir) {
  json d = json::parse(read_file(models("glTF2/simple_skin/simple_skin.gltf")));
  const size_t n = d["accessors"][d["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()]["count"];
  std::vector<float> uv;
  for (size_t i = 0; i < n; ++i) uv.push_back(float(i % 2)), uv.push_back(float(i) / float(n));
  const auto* b = reinterpret_cast<const unsigned char*>(uv.data());
  d["buffers"].push_back({{"byteLength", uv.size() * 4},
                          {"uri", "data:application/octet-stream;base64," + cereal::base64::encode(b, uv.size() * 4)}});
  d["bufferViews"].push_back({{"buffer", d["buffers"].size() - 1}, {"byteLength", uv.size() * 4}});
  d["accessors"].push_back(
      {{"bufferView", d["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}});
  d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = d["accessors"].size() - 1;
  d["meshes"][0]["primitives"][0]["material"] = 0;

  write_png(dir / "base.png", 8, 8, [](int x, int y) {
    return std::array<unsigned char, 4>{200, 90, uchar(x * 30), uchar(y * 30 + 20)};
  });
  write_png(dir / "normal.png", 8, 8, [](int x, int) {
    return std::array<unsigned char, 4>{uchar(120 + x), 130, 250, 255};
  });
  write_png(dir / "orm.png", 4, 4, [](int x, int y) {
    return std::array<unsigned char, 4>{200, uchar(40 * x), uchar(50 * y), 255};
  });
  write_png(dir / "spec color.png", 4, 4, [](int, int) { return std::array<unsigned char, 4>{250, 240, 230, 255}; });
  std::ofstream(dir / "glow.ktx2", std::ios::binary) << tiny_ktx2();
  d["images"] = json::array({{{"uri", "base.png"}, {"name", "base"}},
                             {{"uri", "normal.png"}},
                             {{"uri", "orm.png"}, {"mimeType", "image/png"}},
                             {{"uri", "spec%20color.png"}},
                             {{"uri", "glow.ktx2"}, {"mimeType", "image/ktx2"}}});
  d["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33648}},
                               {{"magFilter", 9729}, {"minFilter", 9987}}});
  d["textures"] = json::array({{{"source", 0}, {"sampler", 0}, {"name", "baseTex"}},
                               {{"source", 1}, {"sampler", 1}},
                               {{"source", 2}},
                               {{"source", 3}, {"sampler", 1}},
                               {{"extensions", {{"KHR_texture_basisu", {{"source", 4}}}}}, {"sampler", 1}}});
  d["materials"] = json::array({json::parse(R"({
    "name": "Skin PBR",
    "pbrMetallicRoughness": {
      "baseColorFactor": [0.9, 0.8, 0.7, 1.0],
      "baseColorTexture": {"index": 0, "texCoord": 0},
      "metallicFactor": 0.3, "roughnessFactor": 0.6,
      "metallicRoughnessTexture": {"index": 2}
    },
    "normalTexture": {"index": 1, "scale": 0.8,
                      "extensions": {"KHR_texture_transform": {"offset": [0.1, 0.2], "rotation": 0.5, "scale": [2, 2]}}},
    "occlusionTexture": {"index": 2, "strength": 0.6},
    "emissiveTexture": {"index": 4},
    "emissiveFactor": [0.5, 0.25, 0.125],
    "alphaMode": "MASK", "alphaCutoff": 0.3,
    "doubleSided": true,
    "extensions": {
      "KHR_materials_specular": {"specularFactor": 0.7, "specularColorFactor": [0.9, 1.0, 0.8],
                                 "specularColorTexture": {"index": 3}},
      "KHR_materials_ior": {"ior": 1.45}
    },
    "extras": {"author": "test", "Texture": {"index": 99}}
  })")});
  d["extensionsUsed"] = {"KHR_texture_transform", "KHR_texture_basisu", "KHR_materials_specular", "KHR_materials_ior"};
  d["extensionsRequired"] = {"KHR_texture_basisu"};
  const fs::path out = dir / "pbr_skin.gltf";
  std::ofstream(out) << d.dump(1);
  return out;
}

}  // namespace

TEST(Materials, EveryFieldOfAGltfMaterialAndItsImagesComeThroughAsTheInputHasThem) {
  const fs::path dir = scratch("pbr_skin");
  const fs::path input = pbr_skin(dir);
  EXPECT_TRUE(validator_errors(input.string()).empty()) << "the fixture itself is valid";
  lod_of(input.string(), dir / "chain.glb", "--lods 0.75,0.5");
  lod_of(input.string(), dir / "lod.gltf", "--ratio 0.5");
  for (const char* name : {"chain_lod1.glb", "chain_lod2.glb", "lod.gltf"}) {
    const fs::path out = dir / name;
    expect_same_materials(input, out);
    EXPECT_TRUE(validator_errors(out.string()).empty()) << out;
    const Doc o = load(out);
    EXPECT_EQ(o.j["materials"][0]["extras"]["author"], "test");
    EXPECT_EQ(o.j["materials"][0]["extras"]["Texture"]["index"], 99) << "extras are the author's, left as they are";
    // The KTX2 image byte for byte, its texture's source inside KHR_texture_basisu, required as in the input.
    bool ktx2 = false;
    for (size_t i = 0; i < o.j["images"].size(); ++i)
      if (o.j["images"][i]["mimeType"] == "image/ktx2") ktx2 = image_bytes(o, int(i)) == tiny_ktx2();
    EXPECT_TRUE(ktx2);
    EXPECT_EQ(o.j["extensionsRequired"], json::array({"KHR_texture_basisu"}));
    // One texture for occlusion and metallic-roughness, as in the input: 5 textures, 5 images.
    EXPECT_EQ(o.j["textures"].size(), 5u);
    EXPECT_EQ(o.j["images"].size(), 5u);
  }
}

TEST(Materials, ClearCoatMaterialsAndTheirTexturesComeThrough) {
  const fs::path out = scratch("clearcoat") / "lod.glb";
  const std::string input = models("glTF2/ClearCoat-glTF/ClearCoatTest.gltf");
  lod_of(input, out);
  expect_same_materials(input, out);
  // The input's primitive with a clear-coat normal map but no normal map and no tangents is invalid
  // (MESH_PRIMITIVE_NO_TANGENT_SPACE) as it comes, its normal-mapped ones warned about; the LOD carries
  // tangents wherever a material needs them, so the validator has nothing to say about tangent space.
  EXPECT_EQ(validator_errors(input), std::vector<std::string>{"MESH_PRIMITIVE_NO_TANGENT_SPACE"});
  EXPECT_TRUE(validator_errors(out.string()).empty());
  const auto v = omsk_test::run_validator(out.string());
  EXPECT_EQ(v.output.find("TANGENT_SPACE"), std::string::npos) << v.output;
  // Every image once, however many textures and materials show it (the input has 10 textures of 6 images).
  EXPECT_EQ(load(out).j["images"].size(), 6u);
}

TEST(Materials, WhatNeedsTangentsIsKnownForTheMeshWriter) {
  SkinnedMesh mesh;
  import_skinned(models("glTF2/ClearCoat-glTF/ClearCoatTest.gltf"), mesh);
  std::map<std::string, bool> needs;
  for (const Material& m : materials(mesh)) needs[m.name] = needs_tangent_space(m);
  EXPECT_FALSE(needs.at("Simple_Coated"));
  EXPECT_TRUE(needs.at("BaseNorm_Base")) << "a normal map";
  EXPECT_TRUE(needs.at("CoatNorm_Coated")) << "a clear-coat normal map";
  EXPECT_FALSE(needs_tangent_space(Material{}));
}

TEST(Materials, TextureTransformsSamplersAndEachFacesMaterialComeThrough) {
  // assimp numbers this file's materials in another order than the file (it reads them as it meets them).
  const fs::path out = scratch("transform") / "lod.gltf";
  const std::string input = models("glTF2/textureTransform/TextureTransformTest.gltf");
  lod_of(input, out, "--ratio 1");
  expect_same_materials(input, out);
  EXPECT_TRUE(validator_errors(out.string()).empty());
  auto expected = triangles_per_material(input);
  EXPECT_EQ(triangles_per_material(out), expected);
}

TEST(Materials, SpecularGlossinessIsCarriedAsTheExtension) {
  const fs::path out = scratch("specgloss") / "lod.glb";
  const std::string input = models("glTF2/BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf");
  lod_of(input, out, "--ratio 1");
  expect_same_materials(input, out);
  EXPECT_TRUE(validator_errors(out.string()).empty());
  const Doc o = load(out);
  EXPECT_TRUE(o.j["materials"][0]["extensions"].contains("KHR_materials_pbrSpecularGlossiness"));
}

TEST(Materials, ImagesOfAGlbAndBesideAGltfAreKeptByteForByte) {
  for (const char* rel : {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
                          "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    const fs::path out = scratch("box") / "lod.glb";
    lod_of(models(rel), out, "--ratio 1");
    expect_same_materials(models(rel), out);
    const Doc o = load(out);
    ASSERT_EQ(o.j["images"].size(), 1u) << rel;
    EXPECT_EQ(image_bytes(o, 0), read_file(models("glTF2/BoxTextured-glTF/CesiumLogoFlat.png"))) << rel;
  }
}

TEST(Materials, AMissingGltfImageIsOneWarningAndTheMaterialKeepsTheRest) {
  const fs::path dir = scratch("missing");
  fs::copy_file(models("glTF2/BoxTextured-glTF/BoxTextured.gltf"), dir / "BoxTextured.gltf");
  fs::copy_file(models("glTF2/BoxTextured-glTF/BoxTextured0.bin"), dir / "BoxTextured0.bin");
  SkinnedMesh mesh;
  const auto rep = import_skinned((dir / "BoxTextured.gltf").string(), mesh);
  size_t lines = 0;
  for (const auto& w : rep.warnings)
    lines += w.find("CesiumLogoFlat.png") != std::string::npos && w.find("not found") != std::string::npos &&
             w.find("\"Texture\"") != std::string::npos;
  EXPECT_EQ(lines, 1u);
  const fs::path out = dir / "lod.glb";
  lod_of((dir / "BoxTextured.gltf").string(), out, "--ratio 1");
  EXPECT_TRUE(validator_errors(out.string()).empty());
  const Doc o = load(out);
  EXPECT_FALSE(o.j["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"));
  EXPECT_EQ(o.j["materials"][0]["pbrMetallicRoughness"]["metallicFactor"], 0.0);
  EXPECT_FALSE(o.j.contains("images"));
}

TEST(Materials, AGltfImageAtAnAbsoluteWindowsPathIsFoundBesideTheInput) {
  const fs::path dir = scratch("windows");
  std::string text = read_file(models("glTF2/BoxTextured-glTF/BoxTextured.gltf"));
  const std::string from = "\"CesiumLogoFlat.png\"";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "\"C:\\\\Users\\\\artist\\\\CesiumLogoFlat.png\"");
  std::ofstream(dir / "BoxTextured.gltf") << text;
  fs::copy_file(models("glTF2/BoxTextured-glTF/BoxTextured0.bin"), dir / "BoxTextured0.bin");
  fs::copy_file(models("glTF2/BoxTextured-glTF/CesiumLogoFlat.png"), dir / "CesiumLogoFlat.png");
  SkinnedMesh mesh;
  const auto rep = import_skinned((dir / "BoxTextured.gltf").string(), mesh);
  EXPECT_FALSE(said(rep.warnings, "CesiumLogoFlat.png"));
  const Material& m = materials(mesh).at(0);
  ASSERT_EQ(m.textures.size(), 1u);
  const std::string png = read_file(dir / "CesiumLogoFlat.png");
  EXPECT_EQ(m.textures[0].images.at(0)->data, std::vector<unsigned char>(png.begin(), png.end()));
}

TEST(Materials, FbxMetalRoughMapsAndFactorsBecomeGltfPbr) {
  const fs::path dir = scratch("fbx");
  fs::copy_file(models("FBX/maxPbrMaterial_metalRough.fbx"), dir / "pbr.fbx");
  fs::create_directories(dir / "Textures");
  using px = std::array<unsigned char, 4>;
  write_png(dir / "Textures/albedo.png", 8, 8, [](int, int) { return px{200, 100, 50, 255}; });
  write_png(dir / "Textures/normal.png", 8, 8, [](int, int) { return px{128, 128, 255, 255}; });
  write_png(dir / "Textures/emission.png", 8, 8, [](int, int) { return px{255, 255, 0, 255}; });
  write_png(dir / "Textures/occlusion.png", 8, 8, [](int, int) { return px{180, 180, 180, 255}; });
  write_png(dir / "Textures/opacity.png", 8, 8, [](int x, int) {
    return px{uchar(x * 32), uchar(x * 32), uchar(x * 32), 255};
  });
  write_png(dir / "Textures/metalness.png", 4, 4, [](int, int) { return px{64, 64, 64, 255}; });
  write_png(dir / "Textures/roughness.png", 8, 8, [](int, int) { return px{160, 160, 160, 255}; });
  const fs::path out = dir / "lod.glb";
  lod_of((dir / "pbr.fbx").string(), out, "--ratio 1");
  EXPECT_TRUE(validator_errors(out.string()).empty());
  const Doc o = load(out);
  ASSERT_EQ(o.j["materials"].size(), 1u);
  const json& m = o.j["materials"][0];
  const json& pbr = m["pbrMetallicRoughness"];
  // 3ds Max's own values (assimp's roughnessFactor for FBX is made up from the Phong shininess).
  EXPECT_NEAR(pbr["metallicFactor"].get<double>(), 0.25, 1e-6);
  EXPECT_NEAR(pbr["roughnessFactor"].get<double>(), 0.5, 1e-6);
  EXPECT_EQ(pbr["baseColorFactor"], json::array({0.0, 1.0, 1.0, 1.0}));
  for (const char* t : {"normalTexture", "occlusionTexture", "emissiveTexture"}) EXPECT_TRUE(m.contains(t)) << t;
  EXPECT_EQ(m["alphaMode"], "BLEND") << "an opacity map";
  // Emission 3.14 (colour times luminance): the colour's direction, the rest as emissive strength.
  ASSERT_EQ(m["emissiveFactor"].size(), 3u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m["emissiveFactor"][c].get<double>(), c < 2 ? 1.0 : 0.0, 1e-6);
  EXPECT_NEAR(m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<double>(), 3.14159, 1e-4);
  auto texels = [&](const json& info) {
    const int src = o.j["textures"][info["index"].get<int>()]["source"];
    const std::string b = image_bytes(o, src);
    Image img{"", "image/png", std::vector<unsigned char>(b.begin(), b.end())};
    std::vector<unsigned char> rgba;
    int w = 0, h = 0;
    EXPECT_TRUE(decode_rgba(img, rgba, w, h));
    return rgba;
  };
  // Roughness in green, metalness in blue, one image; the opacity map is the base colour's alpha.
  const auto mr = texels(pbr["metallicRoughnessTexture"]);
  ASSERT_GE(mr.size(), 4u);
  EXPECT_EQ(mr[1], 160);
  EXPECT_EQ(mr[2], 64);
  const auto base = texels(pbr["baseColorTexture"]);
  ASSERT_GE(base.size(), 8u * 4);
  EXPECT_EQ(base[0], 200);
  EXPECT_EQ(base[3], 0);
  EXPECT_EQ(base[4 * 7 + 3], 224);
}

TEST(Materials, FbxMapsThatCannotBeFoundAreNamedAndTheFactorsStay) {
  SkinnedMesh mesh;
  const auto rep = import_skinned(models("FBX/maxPbrMaterial_metalRough.fbx"), mesh);
  for (const char* f : {"albedo", "normal", "emission", "occlusion", "opacity", "metalness", "roughness"}) {
    size_t lines = 0;
    for (const auto& w : rep.warnings) lines += w.find(std::string("Textures\\") + f + ".png") != std::string::npos;
    EXPECT_EQ(lines, 1u) << f;
  }
  const json g = json::parse(materials(mesh).at(0).gltf);
  EXPECT_NEAR(g["pbrMetallicRoughness"]["metallicFactor"].get<double>(), 0.25, 1e-6);
  EXPECT_FALSE(g["pbrMetallicRoughness"].contains("metallicRoughnessTexture"));
}

TEST(Materials, ATwoSidedColladaMaterialBecomesDoubleSided) {
  // The first effect (material "top") made two-sided the way Google Earth and Okino write it.
  const fs::path dir = scratch("dae");
  std::string text = read_file(models("Collada/kwxport_test_vcolors.dae"));
  const std::string end = "</profile_COMMON>";
  ASSERT_NE(text.find(end), std::string::npos);
  text.replace(text.find(end), end.size(),
               "<extra><technique profile=\"GOOGLEEARTH\"><double_sided>1</double_sided></technique></extra>" + end);
  std::ofstream(dir / "two_sided.dae") << text;
  const fs::path out = dir / "lod.glb";
  lod_of((dir / "two_sided.dae").string(), out, "--ratio 1");
  EXPECT_TRUE(validator_errors(out.string()).empty());
  const Doc o = load(out);
  std::vector<std::string> double_sided;
  for (const json& m : o.j["materials"])
    if (m.value("doubleSided", false)) double_sided.push_back(m.value("name", ""));
  EXPECT_EQ(double_sided, std::vector<std::string>{"top"});
}

// An OBJ quad whose material has the given extra .mtl lines (a base-colour map always).
json obj_material(const fs::path& dir, const std::string& mtl_lines, std::vector<std::string>& warnings) {
  std::ofstream(dir / "quad.obj") << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                     "vt 0 1\nusemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  std::ofstream(dir / "quad.mtl") << "newmtl m\nKd 0.5 0.5 0.5\nmap_Kd base.png\n" << mtl_lines;
  write_png(dir / "base.png", 4, 4, [](int, int) { return std::array<uchar, 4>{90, 80, 70, 255}; });
  SkinnedMesh mesh;
  warnings = import_skinned((dir / "quad.obj").string(), mesh).warnings;
  for (const Material& m : materials(mesh))
    if (m.name == "m") return json::parse(m.gltf);
  ADD_FAILURE() << "no material m";
  return json();
}

TEST(Materials, ABumpMapIsANormalMapOnlyWhenItsPixelsAreOne) {
  const fs::path dir = scratch("obj_bump");
  write_png(dir / "nrm.png", 8, 8, [](int x, int y) {
    return std::array<uchar, 4>{uchar(110 + 4 * x), uchar(110 + 4 * y), 240, 255};
  });
  write_png(dir / "height.png", 8, 8, [](int x, int) {
    return std::array<uchar, 4>{uchar(30 * x), uchar(30 * x), uchar(30 * x), 255};
  });
  std::vector<std::string> warnings;
  const json normal = obj_material(dir, "map_bump nrm.png\n", warnings);
  EXPECT_TRUE(normal.contains("normalTexture"));
  const json height = obj_material(dir, "map_bump height.png\n", warnings);
  EXPECT_FALSE(height.contains("normalTexture"));
  EXPECT_TRUE(said(warnings, "height map \"height.png\" of material \"m\" is not a normal map"));
}

TEST(Materials, OpacityMakesBlendAndMapsWithoutAPlaceInGltfAreNamed) {
  const fs::path dir = scratch("obj_alpha");
  write_png(dir / "spec.png", 2, 2, [](int, int) { return std::array<uchar, 4>{255, 255, 255, 255}; });
  std::vector<std::string> warnings;
  const json m = obj_material(dir, "d 0.4\nmap_Ks spec.png\n", warnings);
  EXPECT_EQ(m["alphaMode"], "BLEND");
  EXPECT_TRUE(m["pbrMetallicRoughness"].contains("baseColorTexture"));
  EXPECT_TRUE(said(warnings, "specular map \"spec.png\""));
  SkinnedMesh mesh;
  import_skinned((dir / "quad.obj").string(), mesh);
  for (const Material& mat : materials(mesh))
    if (mat.name == "m") {
      EXPECT_NEAR(mat.base_color[3], 0.4, 1e-6) << "the opacity is the base colour's alpha";
    }
}

TEST(Materials, ImageFormatsAreRecognisedByTheirBytes) {
  auto bytes = [](const std::string& s) { return std::vector<unsigned char>(s.begin(), s.end()); };
  EXPECT_EQ(gltf_mime_type(bytes(tiny_ktx2())), "image/ktx2");
  EXPECT_EQ(gltf_mime_type(bytes(std::string("RIFF\x10\0\0\0WEBPVP8 ", 16))), "image/webp");
  EXPECT_EQ(gltf_mime_type(bytes("\x89PNG\r\n")), "image/png");
  EXPECT_EQ(gltf_mime_type(bytes("\xFF\xD8\xFF\xE0")), "image/jpeg");
  EXPECT_EQ(gltf_mime_type(bytes("BM....")), "");
}
