#include "OpenMeshSkinned/IO/ImportMaterial.hh"

#include "OpenMeshSkinned/IO/Textures.hh"

#include <assimp/material.h>
#include <assimp/scene.h>

namespace OpenMeshSkinned {

Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source_dir,
                       std::vector<std::string>& warnings) {
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
