// The images behind an assimp material: a Quake model's skin found by its name, embedded textures before
// files, bump maps told from normal maps, and two maps packed into one glTF image.
#include "run_command.hh"

#include <OpenMeshSkinned/IO/MaterialImages.hh>
#include <OpenMeshSkinned/IO/Textures.hh>

#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {

Image solid(int w, int h, unsigned char r, unsigned char g, unsigned char b, unsigned char a, const char* name) {
  std::vector<unsigned char> px(size_t(w) * h * 4);
  for (size_t i = 0; i < px.size(); i += 4) px[i] = r, px[i + 1] = g, px[i + 2] = b, px[i + 3] = a;
  Image out;
  EXPECT_TRUE(encode_rgba_png(px.data(), w, h, name, out));
  return out;
}

void write_png(const fs::path& p, const Image& img) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(img.data.data()), img.data.size());
}

}  // namespace

TEST(MaterialImages, PackTakesTheLargerSizeAndPassesNullForAMissingInput) {
  const Image rough = solid(4, 2, 100, 0, 0, 255, "rough.png");
  const Image metal = solid(2, 8, 30, 0, 0, 255, "metal.png");
  Image out;
  ASSERT_TRUE(pack_images(&rough, &metal, out, [](unsigned char* o, const unsigned char* r, const unsigned char* m) {
    o[0] = 255, o[1] = r[0], o[2] = m[0], o[3] = 255;
  }));
  EXPECT_EQ(out.name, "rough_packed.png");
  EXPECT_EQ(out.mime_type, "image/png");
  std::vector<unsigned char> px;
  int w = 0, h = 0;
  ASSERT_TRUE(decode_rgba(out, px, w, h));
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 8);
  EXPECT_EQ(px[1], 100);
  EXPECT_EQ(px[2], 30);

  bool saw_null = false;
  ASSERT_TRUE(pack_images(nullptr, &metal, out, [&](unsigned char* o, const unsigned char* r, const unsigned char*) {
    saw_null |= r == nullptr;
    o[0] = o[1] = o[2] = o[3] = 255;
  }));
  EXPECT_TRUE(saw_null);
  EXPECT_EQ(out.name, "metal_packed.png");
}

TEST(MaterialImages, PackFailsOnAnImageThatDoesNotDecode) {
  Image broken;
  broken.name = "broken.png";
  broken.data = {0x89, 'P', 'N', 'G', 1, 2, 3};
  const Image fine = solid(2, 2, 1, 2, 3, 255, "fine.png");
  Image out;
  EXPECT_FALSE(pack_images(&broken, &fine, out, [](unsigned char*, const unsigned char*, const unsigned char*) {}));
}

TEST(MaterialImages, ANormalMapIsToldFromAHeightMap) {
  EXPECT_TRUE(looks_like_normal_map(solid(8, 8, 128, 128, 255, 255, "n.png")));
  EXPECT_FALSE(looks_like_normal_map(solid(8, 8, 140, 140, 140, 255, "grey.png")));
  EXPECT_FALSE(looks_like_normal_map(solid(8, 8, 255, 20, 20, 255, "red.png")));
}

TEST(MaterialImages, AQuakeSkinIsTheOneImageNamedAfterTheModel) {
  const fs::path dir = omsk_test::scratch_dir("material_images", "skin");
  const std::string model = (dir / "faerie.md2").string();
  std::ofstream(model) << "x";
  std::vector<std::string> found;
  EXPECT_EQ(image_named_after(model, found), "");
  EXPECT_TRUE(found.empty());
  Image img;
  std::string guessed, problem;
  EXPECT_FALSE(guess_skin_image(model, dir.string(), img, guessed, problem));
  EXPECT_NE(problem.find("no image beside it"), std::string::npos) << problem;

  write_png(dir / "Faerie2.png", solid(2, 2, 9, 9, 9, 255, "Faerie2.png"));
  std::ofstream(dir / "faerie.txt") << "not an image";
  found.clear();
  EXPECT_EQ(image_named_after(model, found), "Faerie2.png");
  ASSERT_TRUE(guess_skin_image(model, dir.string(), img, guessed, problem)) << problem;
  EXPECT_EQ(guessed, "Faerie2.png");
  EXPECT_EQ(img.mime_type, "image/png");

  write_png(dir / "faerie_alt.png", solid(2, 2, 9, 9, 9, 255, "faerie_alt.png"));
  found.clear();
  EXPECT_EQ(image_named_after(model, found), "");
  EXPECT_EQ(found, (std::vector<std::string>{"Faerie2.png", "faerie_alt.png"}));
  problem.clear();
  EXPECT_FALSE(guess_skin_image(model, dir.string(), img, guessed, problem));
  EXPECT_NE(problem.find("several images beside it are named after the model (Faerie2.png, faerie_alt.png)"),
            std::string::npos)
      << problem;
}

TEST(MaterialImages, AnEmbeddedTextureComesBeforeAFileOfTheSameName) {
  const fs::path dir = omsk_test::scratch_dir("material_images", "embedded");
  write_png(dir / "skin.png", solid(2, 2, 0, 0, 0, 255, "skin.png"));
  aiScene scene;
  scene.mNumTextures = 1;
  scene.mTextures = new aiTexture*[1];
  auto* t = scene.mTextures[0] = new aiTexture;
  t->mWidth = 3, t->mHeight = 1;
  t->pcData = new aiTexel[3];
  for (int i = 0; i < 3; ++i) t->pcData[i] = aiTexel{10, 20, 30, 255};  // aiTexel is b, g, r, a
  t->mFilename = aiString("skin.png");
  Image img;
  std::string problem;
  // By the embedded texture's own file name: a file of that name beside the model (black) must not win.
  ASSERT_TRUE(fetch_image(&scene, "skin.png", dir.string(), img, problem)) << problem;
  std::vector<unsigned char> px;
  int w = 0, h = 0;
  ASSERT_TRUE(decode_rgba(img, px, w, h));
  EXPECT_EQ(w, 3);
  EXPECT_EQ(h, 1);
  EXPECT_EQ(int(px[0]), 30);  // red, from the texel's r
  EXPECT_EQ(int(px[2]), 10);

  ASSERT_TRUE(fetch_image(&scene, "*0", dir.string(), img, problem)) << problem;  // and by its index
  ASSERT_TRUE(fetch_image(&scene, "other.png", dir.string(), img, problem) == false);
  EXPECT_FALSE(problem.empty());
}
