#include "OpenMeshSkinned/IO/AssimpMaterial.hh"

#include "OpenMeshSkinned/IO/MaterialImages.hh"
#include "OpenMeshSkinned/IO/Textures.hh"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace OpenMeshSkinned {

namespace {

// assimp's MD2/MDL readers name this texture when the file names no skin (Quake keeps skins beside the
// model, under names the model does not store).
constexpr const char* kNoSkinPlaceholder = "$texture_dummy.bmp";

using json = nlohmann::json;

// One texture of an assimp material, read.
struct Found {
  std::string stored;  // as the material names it
  Image image;
  unsigned uv = 0;  // which UV set
  aiUVTransform transform;
  bool has_transform = false;
  int wrap[2] = {0, 0};  // aiTextureMapMode along U and V
};

// Maps one assimp material; every texture it keeps is read once.
class Mapper {
public:
  Mapper(const aiScene* scene, const aiMaterial* m, const std::string& source, std::vector<std::string>& warnings)
      : scene_(scene),
        m_(m),
        source_(source),
        warnings_(warnings),
        dir_(std::filesystem::absolute(std::filesystem::path(source)).parent_path().string()) {
    aiString name;
    if (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) mat_.name = name.C_Str();
  }

  // Texture 0 of \p type, when the material names one; a missing or unreadable image is a warning.
  bool named(aiTextureType type, std::string& stored) const {
    aiString tex;
    if (m_->GetTexture(type, 0, &tex) != AI_SUCCESS || tex.length == 0) return false;
    stored = tex.C_Str();
    return true;
  }
  bool texture(aiTextureType type, Found& f, const char* what) {
    if (!named(type, f.stored)) return false;
    std::string problem;
    bool ok = false;
    if (f.stored == kNoSkinPlaceholder) {
      std::string guess;
      ok = guess_skin_image(source_, dir_, f.image, guess, problem);
      if (ok) {
        warnings_.push_back("the file names no skin texture: using " + guess +
                            ", the one image beside it named after the model");
        f.stored = guess;
      }
    } else {
      ok = fetch_image(scene_, f.stored, dir_, f.image, problem);
    }
    if (!ok) {
      warnings_.push_back(std::string(what) + " \"" + f.stored + "\" of material \"" + mat_.name + "\" " + problem +
                          ": the material is kept without it");
      return false;
    }
    m_->Get(AI_MATKEY_UVWSRC(type, 0), f.uv);
    f.has_transform = m_->Get(AI_MATKEY_UVTRANSFORM(type, 0), f.transform) == AI_SUCCESS;
    m_->Get(AI_MATKEY_MAPPINGMODE_U(type, 0), f.wrap[0]);
    m_->Get(AI_MATKEY_MAPPINGMODE_V(type, 0), f.wrap[1]);
    return true;
  }

  // A texture reference to \p f's image (or \p image, made from it) as glTF has it.
  json reference(const Found& f, const Image* image = nullptr) {
    Texture tex;
    tex.images.push_back(std::make_shared<const Image>(image ? *image : f.image));
    tex.gltf = json{{"source", 0}}.dump();
    auto wrap = [](int mode) {
      return mode == aiTextureMapMode_Clamp ? 33071 : mode == aiTextureMapMode_Mirror ? 33648 : 10497;
    };
    if (wrap(f.wrap[0]) != 10497 || wrap(f.wrap[1]) != 10497)
      tex.sampler = json{{"wrapS", wrap(f.wrap[0])}, {"wrapT", wrap(f.wrap[1])}}.dump();
    mat_.textures.push_back(std::move(tex));
    json info{{"index", mat_.textures.size() - 1}};
    if (f.uv > 0) info["texCoord"] = f.uv;
    const aiUVTransform& t = f.transform;
    if (f.has_transform && (t.mTranslation != aiVector2D(0, 0) || t.mScaling != aiVector2D(1, 1) || t.mRotation != 0)) {
      json tt = json::object();
      if (t.mTranslation != aiVector2D(0, 0)) tt["offset"] = {t.mTranslation.x, t.mTranslation.y};
      if (t.mRotation != 0) tt["rotation"] = t.mRotation;
      if (t.mScaling != aiVector2D(1, 1)) tt["scale"] = {t.mScaling.x, t.mScaling.y};
      info["extensions"]["KHR_texture_transform"] = tt;
    }
    return info;
  }

  Material map();

private:
  float raw_float(const char* key, float fallback) const {
    float v = fallback;
    m_->Get(key, 0, 0, v);
    return v;
  }
  bool base_colour_and_opacity(json& pbr);
  void metallic_roughness(json& pbr);
  void normal(json& g);
  void occlusion(json& g);
  void emissive(json& g);
  void report_unmapped() const;

  // Both maps' images packed into one (either may be absent).
  static bool pack(const Found* a, const Found* b, Image& out, const TexelPacker& texel) {
    return pack_images(a ? &a->image : nullptr, b ? &b->image : nullptr, out, texel);
  }

  const aiScene* scene_;
  const aiMaterial* m_;
  const std::string& source_;
  std::vector<std::string>& warnings_;
  const std::string dir_;
  Material mat_;
};

Material Mapper::map() {
  json g = json::object();
  json pbr = json::object();
  const bool blend = base_colour_and_opacity(pbr);
  metallic_roughness(pbr);
  g["pbrMetallicRoughness"] = pbr;
  normal(g);
  occlusion(g);
  emissive(g);
  if (blend) g["alphaMode"] = "BLEND";
  int two_sided = 0;
  if (m_->Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS && two_sided) g["doubleSided"] = true;
  report_unmapped();
  mat_.gltf = g.dump();
  return mat_;
}

// The base colour and its texture; an opacity below 1 or an opacity map (which goes into the base colour's
// alpha, where glTF keeps opacity). True when the material blends.
bool Mapper::base_colour_and_opacity(json& pbr) {
  Material& out = mat_;
  aiColor4D c;
  if (m_->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m_->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
    out.base_color[0] = c.r, out.base_color[1] = c.g, out.base_color[2] = c.b, out.base_color[3] = c.a;
  }
  bool blend = false;
  float opacity = 1.0f;
  if (m_->Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f) {
    if (opacity > 0.0f) {
      out.base_color[3] = opacity;
      blend = true;
    } else {
      // A material nobody can see is an exporter's mistake far more often than an artist's wish.
      warnings_.push_back("material \"" + out.name + "\" has opacity 0 (invisible): taken as opaque");
    }
  }

  Found base, alpha;
  const bool has_base =
      texture(aiTextureType_BASE_COLOR, base, "texture") || texture(aiTextureType_DIFFUSE, base, "texture");
  const bool has_alpha = texture(aiTextureType_OPACITY, alpha, "opacity map");
  if (has_base) out.base_color_texture = base.stored;
  if (!has_alpha) {
    if (has_base) pbr["baseColorTexture"] = reference(base);
    return blend;
  }
  if (has_base && alpha.stored == base.stored) {
    pbr["baseColorTexture"] = reference(base);  // the base colour's own alpha
    return true;
  }
  // The opacity map's alpha when it has one, else its grey, becomes the base colour's alpha.
  std::vector<unsigned char> apx;
  int aw, ah;
  bool own_alpha = false;
  if (decode_rgba(alpha.image, apx, aw, ah))
    for (size_t i = 3; i < apx.size() && !own_alpha; i += 4) own_alpha = apx[i] != 255;
  Image merged;
  const bool ok = pack(has_base ? &base : nullptr, &alpha, merged,
                       [&](unsigned char* o, const unsigned char* b, const unsigned char* a) {
                         for (int k = 0; k < 3; ++k) o[k] = b ? b[k] : 255;
                         o[3] = own_alpha ? a[3] : a[0];
                       });
  if (ok) {
    pbr["baseColorTexture"] = reference(has_base ? base : alpha, &merged);
    if (!has_base) out.base_color_texture = merged.name;
  } else {
    warnings_.push_back("opacity map \"" + alpha.stored + "\" of material \"" + out.name +
                        "\" cannot be decoded: the material is kept without it");
    if (has_base) pbr["baseColorTexture"] = reference(base);
  }
  return true;
}

// Metallic-roughness factors and maps. 3ds Max's Physical/PBR materials keep their own values (assimp's
// roughness for FBX is made up from the Phong shininess, and can be negative).
void Mapper::metallic_roughness(json& pbr) {
  float metallic = 0.0f, roughness = 1.0f;
  m_->Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  m_->Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  int max_gloss = 0;
  if (m_->Get("$raw.3dsMax|main|useGlossiness", 0, 0, max_gloss) == AI_SUCCESS) {
    metallic = raw_float("$raw.3dsMax|main|metalness", 0.0f);
    roughness = max_gloss == 1 ? 1.0f - raw_float("$raw.3dsMax|main|glossiness", 0.0f)
                               : raw_float("$raw.3dsMax|main|roughness", roughness);
    aiColor4D bc;
    if (m_->Get("$raw.3dsMax|main|basecolor", 0, 0, bc) == AI_SUCCESS)
      mat_.base_color[0] = bc.r, mat_.base_color[1] = bc.g, mat_.base_color[2] = bc.b;
  }
  pbr["metallicFactor"] = std::clamp(metallic, 0.0f, 1.0f);
  pbr["roughnessFactor"] = std::clamp(roughness, 0.0f, 1.0f);
  Found metal, rough;
  const bool has_metal = texture(aiTextureType_METALNESS, metal, "metalness map");
  bool has_rough = texture(aiTextureType_DIFFUSE_ROUGHNESS, rough, "roughness map");
  bool gloss = false;
  if (!has_rough) gloss = has_rough = texture(aiTextureType_SHININESS, rough, "glossiness map");
  if (has_metal && has_rough && metal.stored == rough.stored && !gloss) {
    pbr["metallicRoughnessTexture"] = reference(metal);  // already packed the glTF way
    return;
  }
  if (!has_metal && !has_rough) return;
  // glTF packs them in one image: roughness in green, metalness in blue.
  Image packed;
  const bool ok = pack(has_rough ? &rough : nullptr, has_metal ? &metal : nullptr, packed,
                       [&](unsigned char* o, const unsigned char* r, const unsigned char* m) {
                         o[0] = 255;
                         o[1] = r ? (gloss ? 255 - r[0] : r[0]) : 255;
                         o[2] = m ? m[0] : 255;
                         o[3] = 255;
                       });
  if (ok)
    pbr["metallicRoughnessTexture"] = reference(has_rough ? rough : metal, &packed);
  else
    warnings_.push_back("metalness/roughness maps of material \"" + mat_.name +
                        "\" cannot be decoded: the material is kept without them");
}

// The normal map (a height map only when its pixels are a normal map's) and its scale.
void Mapper::normal(json& g) {
  Found normal;
  if (texture(aiTextureType_NORMAL_CAMERA, normal, "normal map") ||
      texture(aiTextureType_NORMALS, normal, "normal map")) {
    g["normalTexture"] = reference(normal);
  } else if (named(aiTextureType_HEIGHT, normal.stored)) {
    if (texture(aiTextureType_HEIGHT, normal, "bump map")) {
      if (looks_like_normal_map(normal.image))
        g["normalTexture"] = reference(normal);
      else
        warnings_.push_back("height map \"" + normal.stored + "\" of material \"" + mat_.name +
                            "\" is not a normal map, and glTF has no height maps: dropped");
    }
  }
  float bump = 1.0f;
  if (g.contains("normalTexture") && m_->Get(AI_MATKEY_BUMPSCALING, bump) == AI_SUCCESS && bump != 1.0f)
    g["normalTexture"]["scale"] = bump;
}

void Mapper::occlusion(json& g) {
  Found occlusion;
  if (texture(aiTextureType_AMBIENT_OCCLUSION, occlusion, "occlusion map") ||
      texture(aiTextureType_LIGHTMAP, occlusion, "light map"))
    g["occlusionTexture"] = reference(occlusion);
}

void Mapper::emissive(json& g) {
  Found emissive;
  const bool has_emissive = texture(aiTextureType_EMISSION_COLOR, emissive, "emissive map") ||
                            texture(aiTextureType_EMISSIVE, emissive, "emissive map");
  aiColor3D e(0, 0, 0);
  m_->Get(AI_MATKEY_COLOR_EMISSIVE, e);
  float intensity = 1.0f;
  if (m_->Get(AI_MATKEY_EMISSIVE_INTENSITY, intensity) == AI_SUCCESS) e = e * intensity;
  if (has_emissive) {
    g["emissiveTexture"] = reference(emissive);
    if (e.IsBlack()) e = aiColor3D(1, 1, 1);  // a map with no colour to scale it still glows
  }
  const double brightest = std::max({e.r, e.g, e.b});
  if (brightest > 0.0) {
    // glTF's factor stops at 1; brighter goes to KHR_materials_emissive_strength.
    const double k = std::max(brightest, 1.0);
    g["emissiveFactor"] = {e.r / k, e.g / k, e.b / k};
    if (k > 1.0) g["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", k}};
  }
}

// Maps with no place in glTF PBR, named in one line.
void Mapper::report_unmapped() const {
  std::string dropped;
  int n_dropped = 0;
  const std::pair<aiTextureType, const char*> unmapped[] = {{aiTextureType_SPECULAR, "specular"},
                                                            {aiTextureType_AMBIENT, "ambient"},
                                                            {aiTextureType_DISPLACEMENT, "displacement"},
                                                            {aiTextureType_REFLECTION, "reflection"},
                                                            {aiTextureType_SHEEN, "sheen"},
                                                            {aiTextureType_CLEARCOAT, "clearcoat"},
                                                            {aiTextureType_TRANSMISSION, "transmission"}};
  for (const auto& [type, what] : unmapped) {
    std::string stored;
    if (!named(type, stored)) continue;
    dropped += (dropped.empty() ? "" : ", ") + std::string(what) + " map \"" + stored + "\"";
    ++n_dropped;
  }
  if (!dropped.empty())
    warnings_.push_back("material \"" + mat_.name + "\": its " + dropped + (n_dropped > 1 ? " have" : " has") +
                        " no place in glTF PBR: dropped");
}

}  // namespace

Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source,
                       std::vector<std::string>& warnings) {
  return Mapper(scene, m, source, warnings).map();
}

}  // namespace OpenMeshSkinned
