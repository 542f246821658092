// Textures end up inside every output: files beside the input (relative, absolute Windows paths, other
// formats converted to PNG), images embedded in the input; a missing one is a warning, never a dangling URI.
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/Textures.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {
fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("tex", name); }
std::string models(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }

// The input \p src written to \p dir with its texture reference replaced by \p stored, and \p image
// copied beside it under \p image_name.
std::string rewrite_reference(const std::string& src, const fs::path& dir, const std::string& from,
                              const std::string& stored, const std::string& image, const std::string& image_name) {
  std::ifstream in(src);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, from.size(), stored);
  const fs::path out = dir / fs::path(src).filename();
  std::ofstream(out) << text;
  if (!image.empty()) fs::copy_file(image, dir / image_name, fs::copy_options::overwrite_existing);
  return out.string();
}

// Every image of a written file is inside it (a buffer view), decodes as what it claims, and there is one.
void expect_embedded_images(const std::string& file, size_t n) {
  const tinygltf::Model m = omsk_spec::load(file);
  ASSERT_EQ(m.images.size(), n) << file;
  for (const auto& img : m.images) {
    EXPECT_TRUE(img.uri.empty()) << img.uri;
    EXPECT_GE(img.bufferView, 0);
    EXPECT_TRUE(img.mimeType == "image/png" || img.mimeType == "image/jpeg") << img.mimeType;
    EXPECT_GT(img.width, 0);  // tinygltf decoded it
  }
  ASSERT_FALSE(m.materials.empty());
  EXPECT_GE(m.materials[0].pbrMetallicRoughness.baseColorTexture.index, 0);
}

void lod_of(const std::string& input, const fs::path& out, const std::string& args = "--ratio 0.5") {
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "'" + input + "' -o '" + out.string() + "' " + args + " --quiet",
                                        out.parent_path());
  ASSERT_EQ(r.code, 0) << r.out;
  omsk_test::expect_valid_gltf(out.string());
}
}  // namespace

TEST(Textures, PngBesideAGltfIsEmbedded) {
  const fs::path out = scratch("box") / "box.glb";
  lod_of(models("glTF2/BoxTextured-glTF/BoxTextured.gltf"), out, "--ratio 1");
  expect_embedded_images(out.string(), 1);
}

TEST(Textures, GltfOutputCarriesItsImagesToo) {
  const fs::path out = scratch("boxgltf") / "box.gltf";
  lod_of(models("glTF2/BoxTextured-glTF/BoxTextured.gltf"), out, "--ratio 1");
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("\"uri\": \"CesiumLogoFlat.png\""), std::string::npos) << "no URI to a file beside it";
  expect_embedded_images(out.string(), 1);
}

TEST(Textures, GlbEmbeddedImagesSurvive) {
  const fs::path out = scratch("boxglb") / "box.glb";
  lod_of(models("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"), out, "--ratio 1");
  expect_embedded_images(out.string(), 1);
}

TEST(Textures, RelativeWindowsPathInAnXFile) {
  const fs::path out = scratch("x") / "test_lod.glb";
  lod_of(models("X/test.x"), out);
  expect_embedded_images(out.string(), 1);
}

TEST(Textures, AbsoluteWindowsPathFallsBackToTheFileBesideTheInput) {
  const fs::path dir = scratch("abs");
  const std::string input = rewrite_reference(models("X/test.x"), dir, ".\\\\test.png", "C:/work/assets/turtle1.png",
                                              models("X/test.png"), "turtle1.png");
  const fs::path out = dir / "abs_lod.glb";
  lod_of(input, out);
  expect_embedded_images(out.string(), 1);
}

TEST(Textures, TgaIsConvertedToPng) {
  const fs::path out = scratch("duck") / "duck.glb";
  lod_of(models("Collada/duck.dae"), out);
  expect_embedded_images(out.string(), 1);
  EXPECT_EQ(omsk_spec::load(out.string()).images[0].mimeType, "image/png");
}

TEST(Textures, MissingImageIsAWarningAndTheMaterialStays) {
  const fs::path dir = scratch("missing");
  const std::string input = rewrite_reference(models("X/test.x"), dir, ".\\\\test.png", "gone.png", "", "");
  SkinnedMesh mesh;
  const auto rep = import_skinned(input, mesh);
  bool warned = false;
  for (const auto& w : rep.warnings)
    warned |= w.find("gone.png") != std::string::npos && w.find("not found") != std::string::npos;
  EXPECT_TRUE(warned);
  const fs::path out = dir / "missing.glb";
  lod_of(input, out);
  const tinygltf::Model m = omsk_spec::load(out.string());
  EXPECT_TRUE(m.images.empty());
  EXPECT_FALSE(m.materials.empty());
}

TEST(Textures, EncodeKeepsPngAndJpegAndRejectsGarbage) {
  Image img;
  std::string why;
  const std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,  // signature
                                          0,    0,   0,   0,   'I',  'E',  'N',  'D',  0xAE, 0x42, 0x60, 0x82};
  EXPECT_TRUE(encode_for_gltf(png, "a.png", img, why));
  EXPECT_EQ(img.mime_type, "image/png");
  EXPECT_EQ(img.data, png);
  EXPECT_TRUE(encode_for_gltf({0xFF, 0xD8, 0xFF, 0xE0, 0, 2, 0xFF, 0xD9}, "a.jpg", img, why));
  EXPECT_EQ(img.mime_type, "image/jpeg");
  // Cut short (a truncated file, a corrupt GLB): the validator would refuse the LOD that carried it.
  EXPECT_FALSE(encode_for_gltf(std::vector<unsigned char>(png.begin(), png.end() - 5), "a.png", img, why));
  EXPECT_EQ(why, "a PNG cut short (no IEND chunk where its chunks end)");
  EXPECT_FALSE(encode_for_gltf({0xFF, 0xD8, 0xFF, 0xE0, 0, 2}, "a.jpg", img, why));
  EXPECT_EQ(why, "a JPEG cut short (no end-of-image marker)");
  EXPECT_FALSE(encode_for_gltf({1, 2, 3, 4, 5, 6, 7, 8}, "a.bin", img, why));
  EXPECT_FALSE(why.empty());
}

TEST(Textures, AnMd2ThatNamesNoSkinTextureGetsTheOneImageNamedAfterIt) {
  // faerie.md2 names no skin; faerie2.bmp lies beside it (BMP, so it is converted to PNG).
  OpenMeshSkinned::SkinnedMesh mesh;
  const auto rep = OpenMeshSkinned::import_skinned(std::string(OMSK_TEST_MODELS) + "/MD2/faerie.md2", mesh);
  const auto& mats = OpenMeshSkinned::materials(mesh);
  ASSERT_EQ(mats.size(), 1u);
  EXPECT_EQ(mats[0].base_color_texture, "faerie2.bmp");
  ASSERT_EQ(mats[0].textures.size(), 1u);
  ASSERT_EQ(mats[0].textures[0].images.size(), 1u);
  EXPECT_EQ(mats[0].textures[0].images[0]->mime_type, "image/png");
  EXPECT_FALSE(mats[0].textures[0].images[0]->data.empty());
  bool said = false;
  for (const auto& w : rep.warnings) said |= w.find("using faerie2.bmp") != std::string::npos;
  EXPECT_TRUE(said);
}
