#include "OpenMeshSkinned/IO/ImportMaterial.hh"

#include "OpenMeshSkinned/IO/GltfMaterials.hh"
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/Textures.hh"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <new>

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

// The image \p stored names: embedded ("*N", or a file name FBX and GLB files carry inside themselves)
// before a file beside the source.
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
      std::vector<std::string> found;
      const std::string guess = image_named_after(source_, found);
      if (!guess.empty() && read_texture_file(guess, dir_, f.image, problem)) {
        warnings_.push_back("the file names no skin texture: using " + guess +
                            ", the one image beside it named after the model");
        f.stored = guess;
        ok = true;
      } else {
        std::string listed;
        for (const auto& x : found) listed += (listed.empty() ? "" : ", ") + x;
        problem = found.empty() ? "stands for a skin texture the file does not name, and no image beside it is "
                                  "named after the model"
                  : guess.empty()
                      ? "stands for a skin texture the file does not name, and several images beside it are named "
                        "after the model (" +
                            listed + ")"
                      : problem;
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
  bool is_normal_map(const Image& img) const;
  bool pack(const Found* base, const Found* second, Image& out,
            const std::function<void(unsigned char*, const unsigned char*, const unsigned char*)>& texel) const;

  const aiScene* scene_;
  const aiMaterial* m_;
  const std::string& source_;
  std::vector<std::string>& warnings_;
  const std::string dir_;
  Material mat_;
};

// A tangent-space normal map points mostly along +Z (blue high, red and green around the middle); a
// height map is grey. Some exporters (OBJ's bump, FBX's Bump) store normal maps as height maps.
bool Mapper::is_normal_map(const Image& img) const {
  std::vector<unsigned char> px;
  int w = 0, h = 0;
  if (!decode_rgba(img, px, w, h) || w == 0 || h == 0) return false;
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

// A new RGBA image, as large as the larger of \p base and \p second: \p texel writes each texel from the
// texels of both at the same place (nullptr where an image is absent).
bool Mapper::pack(const Found* base, const Found* second, Image& out,
                  const std::function<void(unsigned char*, const unsigned char*, const unsigned char*)>& texel) const {
  std::vector<unsigned char> a, b;
  int aw = 0, ah = 0, bw = 0, bh = 0;
  if (base && !decode_rgba(base->image, a, aw, ah)) return false;
  if (second && !decode_rgba(second->image, b, bw, bh)) return false;
  const int w = std::max(aw, bw), h = std::max(ah, bh);
  std::vector<unsigned char> px(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto at = [&](const std::vector<unsigned char>& img, int iw, int ih) -> const unsigned char* {
        if (img.empty()) return nullptr;
        return &img[4 * (size_t(y * ih / h) * iw + size_t(x * iw / w))];
      };
      texel(&px[4 * (size_t(y) * w + x)], at(a, aw, ah), at(b, bw, bh));
    }
  const Found* named = base ? base : second;
  return encode_rgba_png(px.data(), w, h, std::filesystem::path(named->image.name).stem().string() + "_packed.png",
                         out);
}

Material Mapper::map() {
  Material& out = mat_;
  json g = json::object();
  json pbr = json::object();
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
  if (has_alpha) {
    blend = true;
    Image merged;
    if (has_base && alpha.stored == base.stored) {
      pbr["baseColorTexture"] = reference(base);  // the base colour's own alpha
    } else {
      // glTF's opacity is the base colour's alpha: the opacity map (its alpha when it has one, else its grey) goes
      // there.
      std::vector<unsigned char> apx;
      int aw, ah;
      bool own_alpha = false;
      if (decode_rgba(alpha.image, apx, aw, ah))
        for (size_t i = 3; i < apx.size() && !own_alpha; i += 4) own_alpha = apx[i] != 255;
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
    }
  } else if (has_base) {
    pbr["baseColorTexture"] = reference(base);
  }

  // Metallic-roughness. 3ds Max's Physical/PBR materials keep their own values (assimp's roughness for FBX
  // is made up from the Phong shininess, and can be negative).
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
      out.base_color[0] = bc.r, out.base_color[1] = bc.g, out.base_color[2] = bc.b;
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
  } else if (has_metal || has_rough) {
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
      warnings_.push_back("metalness/roughness maps of material \"" + out.name +
                          "\" cannot be decoded: the material is kept without them");
  }
  g["pbrMetallicRoughness"] = pbr;

  Found normal;
  if (texture(aiTextureType_NORMAL_CAMERA, normal, "normal map") ||
      texture(aiTextureType_NORMALS, normal, "normal map")) {
    g["normalTexture"] = reference(normal);
  } else if (named(aiTextureType_HEIGHT, normal.stored)) {
    if (texture(aiTextureType_HEIGHT, normal, "bump map")) {
      if (is_normal_map(normal.image))
        g["normalTexture"] = reference(normal);
      else
        warnings_.push_back("height map \"" + normal.stored + "\" of material \"" + out.name +
                            "\" is not a normal map, and glTF has no height maps: dropped");
    }
  }
  float bump = 1.0f;
  if (g.contains("normalTexture") && m_->Get(AI_MATKEY_BUMPSCALING, bump) == AI_SUCCESS && bump != 1.0f)
    g["normalTexture"]["scale"] = bump;

  Found occlusion;
  if (texture(aiTextureType_AMBIENT_OCCLUSION, occlusion, "occlusion map") ||
      texture(aiTextureType_LIGHTMAP, occlusion, "light map"))
    g["occlusionTexture"] = reference(occlusion);

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

  if (blend) g["alphaMode"] = "BLEND";
  int two_sided = 0;
  if (m_->Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS && two_sided) g["doubleSided"] = true;

  // Maps with no place in glTF PBR, named in one line.
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
    warnings_.push_back("material \"" + out.name + "\": its " + dropped + (n_dropped > 1 ? " have" : " has") +
                        " no place in glTF PBR: dropped");
  out.gltf = g.dump();
  return out;
}

}  // namespace

Material read_material(const aiScene* scene, const aiMaterial* m, const std::string& source,
                       std::vector<std::string>& warnings) {
  return Mapper(scene, m, source, warnings).map();
}

std::vector<Material> read_materials(const aiScene* scene, const std::string& source, const std::string& read_path,
                                     std::vector<std::string>& warnings) {
  std::vector<Material> file, out;
  std::vector<int> order;
  bool from_file = false;
  try {
    from_file = read_gltf_materials(read_path, source, file, order, warnings);
  } catch (const IOError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // a field of the wrong type in the file's JSON
    warnings.push_back(std::string("the file's materials could not be read (") + e.what() +
                       "): kept as the reader reports them");
    file.clear();
    order.clear();
  }
  if (from_file) {
    // assimp numbers the materials it read in its own order and appends a default material for primitives
    // without one (glTF's default material is the empty one). Its names must agree with the file's.
    bool agree = order.size() <= scene->mNumMaterials && scene->mNumMaterials <= order.size() + 1;
    for (unsigned m = 0; m < scene->mNumMaterials && agree; ++m) {
      aiString name;
      const std::string reader =
          scene->mMaterials[m]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? name.C_Str() : std::string();
      if (m < order.size()) {
        out.push_back(file[size_t(order[m])]);
        agree = out.back().name.empty() || out.back().name == reader;
      } else {
        Material d;
        d.name = reader;
        d.gltf = "{}";
        out.push_back(std::move(d));
      }
    }
    if (agree) return out;
    warnings.push_back("the file's materials could not be matched to the reader's: kept as the reader reports them");
    out.clear();
  }
  for (unsigned m = 0; m < scene->mNumMaterials; ++m)
    out.push_back(read_material(scene, scene->mMaterials[m], source, warnings));
  return out;
}

}  // namespace OpenMeshSkinned
