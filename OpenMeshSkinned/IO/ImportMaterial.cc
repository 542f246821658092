#include "OpenMeshSkinned/IO/ImportMaterial.hh"

#include "OpenMeshSkinned/IO/Textures.hh"

#include <assimp/material.h>

#include <assimp/scene.h>
#include <algorithm>
#include <cctype>
#include <filesystem>

namespace OpenMeshSkinned {

namespace {

// assimp's MD2/MDL readers name this texture when the file names no skin (Quake keeps skins beside the
// model, under names the model does not store).
constexpr const char* kNoSkinPlaceholder = "$texture_dummy.bmp";

// The one image beside \p source whose name starts with the model's (faerie.md2: faerie2.bmp); empty when
// there is none or more than one (\p found lists them).
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

}  // namespace

Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source,
                       std::vector<std::string>& warnings) {
  const std::string source_dir = std::filesystem::absolute(std::filesystem::path(source)).parent_path().string();
  Material out;
  aiString name;
  if (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
  aiColor4D c;
  if (m->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
    out.base_color[0] = c.r;
    out.base_color[1] = c.g;
    out.base_color[2] = c.b;
    out.base_color[3] = c.a;
  }
  aiString tex;
  if ((m->GetTexture(aiTextureType_BASE_COLOR, 0, &tex) != AI_SUCCESS &&
       m->GetTexture(aiTextureType_DIFFUSE, 0, &tex) != AI_SUCCESS) ||
      tex.length == 0)
    return out;
  out.base_color_texture = tex.C_Str();
  std::string problem;
  bool ok = false;
  // Embedded ("*N", or a file name FBX and GLB files carry inside themselves) before files beside the source.
  if (const aiTexture* et = scene->GetEmbeddedTexture(tex.C_Str())) {
    const std::string name = et->mFilename.length ? et->mFilename.C_Str() : out.base_color_texture;
    if (et->mHeight == 0) {
      const auto* b = reinterpret_cast<const unsigned char*>(et->pcData);
      ok = encode_for_gltf(std::vector<unsigned char>(b, b + et->mWidth), name, out.base_color_image, problem);
    } else {
      std::vector<unsigned char> rgba(size_t(et->mWidth) * et->mHeight * 4);
      for (size_t i = 0; i < size_t(et->mWidth) * et->mHeight; ++i) {
        const aiTexel& t = et->pcData[i];
        rgba[4 * i] = t.r, rgba[4 * i + 1] = t.g, rgba[4 * i + 2] = t.b, rgba[4 * i + 3] = t.a;
      }
      ok = encode_rgba_png(rgba.data(), et->mWidth, et->mHeight, name, out.base_color_image);
      if (!ok) problem = "could not be encoded as PNG";
    }
  } else if (out.base_color_texture == kNoSkinPlaceholder) {
    std::vector<std::string> found;
    const std::string guess = image_named_after(source, found);
    if (!guess.empty() && read_texture_file(guess, source_dir, out.base_color_image, problem)) {
      warnings.push_back("the file names no skin texture: using " + guess +
                         ", the one image beside it named after the model");
      out.base_color_texture = guess;
      return out;
    }
    std::string listed;
    for (const auto& f : found) listed += (listed.empty() ? "" : ", ") + f;
    problem =
        found.empty()   ? "stands for a skin texture the file does not name, and no image beside it is named after the "
                          "model"
        : guess.empty() ? "stands for a skin texture the file does not name, and several images beside it are named "
                          "after the model (" +
                              listed + ")"
                        : problem;
  } else {
    ok = read_texture_file(out.base_color_texture, source_dir, out.base_color_image, problem);
  }
  if (!ok) {
    out.base_color_image = {};
    warnings.push_back("texture \"" + out.base_color_texture + "\" of material \"" + out.name + "\" " + problem +
                       ": the material is kept without it");
  }
  return out;
}

}  // namespace OpenMeshSkinned
