#include "OpenMeshSkinned/IO/MaterialImages.hh"

#include "OpenMeshSkinned/IO/Textures.hh"

#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

namespace OpenMeshSkinned {

std::string image_named_after(const std::string& source, std::vector<std::string>& found) {
  namespace fs = std::filesystem;
  auto lower = [](std::string x) {
    for (char& c : x) c = char(std::tolower(static_cast<unsigned char>(c)));
    return x;
  };
  const fs::path src = fs::absolute(fs::path(source));
  const std::string stem = lower(src.stem().string());
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(src.parent_path(), ec)) {
    const std::string ext = lower(e.path().extension().string());
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".bmp" && ext != ".tga") continue;
    if (lower(e.path().stem().string()).rfind(stem, 0) == 0) found.push_back(e.path().filename().string());
  }
  std::sort(found.begin(), found.end());
  return found.size() == 1 ? found[0] : std::string();
}

bool guess_skin_image(const std::string& source, const std::string& source_dir, Image& out, std::string& guessed,
                      std::string& problem) {
  std::vector<std::string> found;
  const std::string guess = image_named_after(source, found);
  if (!guess.empty() && read_texture_file(guess, source_dir, out, problem)) {
    guessed = guess;
    return true;
  }
  std::string listed;
  for (const auto& x : found) listed += (listed.empty() ? "" : ", ") + x;
  if (found.empty())
    problem = "stands for a skin texture the file does not name, and no image beside it is named after the model";
  else if (guess.empty())
    problem =
        "stands for a skin texture the file does not name, and several images beside it are named after the "
        "model (" +
        listed + ")";
  return false;
}

bool fetch_image(const aiScene* scene, const std::string& stored, const std::string& source_dir, Image& out,
                 std::string& problem) {
  if (const aiTexture* et = scene->GetEmbeddedTexture(stored.c_str())) {
    const std::string name = et->mFilename.length ? et->mFilename.C_Str() : stored;
    if (et->mHeight == 0) {
      const auto* b = reinterpret_cast<const unsigned char*>(et->pcData);
      return encode_for_gltf(std::vector<unsigned char>(b, b + et->mWidth), name, out, problem);
    }
    std::vector<unsigned char> rgba(size_t(et->mWidth) * et->mHeight * 4);
    for (size_t i = 0; i < size_t(et->mWidth) * et->mHeight; ++i) {
      const aiTexel& t = et->pcData[i];
      rgba[4 * i] = t.r, rgba[4 * i + 1] = t.g, rgba[4 * i + 2] = t.b, rgba[4 * i + 3] = t.a;
    }
    if (encode_rgba_png(rgba.data(), et->mWidth, et->mHeight, name, out)) return true;
    problem = "could not be encoded as PNG";
    return false;
  }
  return read_texture_file(stored, source_dir, out, problem);
}

bool looks_like_normal_map(const Image& image) {
  std::vector<unsigned char> px;
  int w = 0, h = 0;
  if (!decode_rgba(image, px, w, h) || w == 0 || h == 0) return false;
  double r = 0, g = 0, b = 0, grey = 0;
  const size_t n = size_t(w) * h;
  for (size_t i = 0; i < n; ++i) {
    const int R = px[4 * i], G = px[4 * i + 1], B = px[4 * i + 2];
    r += R, g += G, b += B;
    grey += std::abs(R - G) < 8 && std::abs(G - B) < 8;
  }
  r /= n, g /= n, b /= n;
  return grey / n < 0.5 && b > 180 && std::abs(r - 128) < 48 && std::abs(g - 128) < 48;
}

bool pack_images(const Image* a, const Image* b, Image& out, const TexelPacker& texel) {
  std::vector<unsigned char> pa, pb;
  int aw = 0, ah = 0, bw = 0, bh = 0;
  if (a && !decode_rgba(*a, pa, aw, ah)) return false;
  if (b && !decode_rgba(*b, pb, bw, bh)) return false;
  const int w = std::max(aw, bw), h = std::max(ah, bh);
  std::vector<unsigned char> px(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto at = [&](const std::vector<unsigned char>& img, int iw, int ih) -> const unsigned char* {
        if (img.empty()) return nullptr;
        return &img[4 * (size_t(y * ih / h) * iw + size_t(x * iw / w))];
      };
      texel(&px[4 * (size_t(y) * w + x)], at(pa, aw, ah), at(pb, bw, bh));
    }
  const Image& named = a ? *a : *b;
  return encode_rgba_png(px.data(), w, h, std::filesystem::path(named.name).stem().string() + "_packed.png", out);
}

}  // namespace OpenMeshSkinned
