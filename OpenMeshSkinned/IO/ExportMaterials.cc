#include "OpenMeshSkinned/IO/ExportMaterials.hh"

#include "OpenMeshSkinned/IO/ExportParts.hh"
#include "OpenMeshSkinned/IO/GltfMaterials.hh"
#include "OpenMeshSkinned/IO/PrintableText.hh"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

namespace OpenMeshSkinned::detail {
namespace {

using json = nlohmann::json;

tinygltf::Value to_value(const json& j) {
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  if (j.is_number_integer()) {
    const auto v = j.get<int64_t>();
    if (v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max()) return tinygltf::Value(int(v));
    return tinygltf::Value(double(v));
  }
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  if (j.is_array()) {
    tinygltf::Value::Array a;
    for (const json& e : j) a.push_back(to_value(e));
    return tinygltf::Value(std::move(a));
  }
  if (j.is_object()) {
    tinygltf::Value::Object o;
    for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_value(*it);
    return tinygltf::Value(std::move(o));
  }
  return tinygltf::Value();
}

// An object's "extensions" and "extras" as tinygltf keeps them.
template <typename T>
void extensions_and_extras(const json& j, T& out) {
  if (j.contains("extensions") && j["extensions"].is_object())
    for (auto it = j["extensions"].begin(); it != j["extensions"].end(); ++it) out.extensions[it.key()] = to_value(*it);
  if (j.contains("extras")) out.extras = to_value(j["extras"]);
}

template <typename Info>
void texture_info(const json& j, Info& out) {
  out.index = j.value("index", -1);
  out.texCoord = j.value("texCoord", 0);
  extensions_and_extras(j, out);
}

std::vector<double> numbers(const json& j, std::vector<double> fallback) {
  if (!j.is_array()) return fallback;
  std::vector<double> v;
  for (const json& e : j) v.push_back(e.get<double>());
  return v;
}

// The texture info's KHR_texture_transform object, or null.
json* texture_transform(json& info) {
  if (!info.contains("extensions") || !info["extensions"].is_object()) return nullptr;
  json& ext = info["extensions"];
  return ext.contains("KHR_texture_transform") && ext["KHR_texture_transform"].is_object()
             ? &ext["KHR_texture_transform"]
             : nullptr;
}

// The UV set a texture info reads: its texCoord, or its transform's where that overrides it.
int tex_coord(const json& info) {
  json copy = info;
  const json* t = texture_transform(copy);
  if (t && t->contains("texCoord") && (*t)["texCoord"].is_number_integer()) return (*t)["texCoord"].get<int>();
  return info.contains("texCoord") && info["texCoord"].is_number_integer() ? info["texCoord"].get<int>() : 0;
}

// A texture info's UV set numbers, the input's, as the output numbers them.
void renumber_tex_coords(json& info, const std::function<int(int)>& uv) {
  const int own = info.contains("texCoord") && info["texCoord"].is_number_integer() ? info["texCoord"].get<int>() : 0;
  if (info.contains("texCoord") || uv(own) != own) info["texCoord"] = uv(own);
  if (json* t = texture_transform(info); t && t->contains("texCoord") && (*t)["texCoord"].is_number_integer())
    (*t)["texCoord"] = uv((*t)["texCoord"].get<int>());
}

bool is_texture_info(const std::string& key, const json& j) {
  return key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && j.is_object() && j.contains("index") &&
         j["index"].is_number_integer();
}

// Renumbers every texture reference of a material object (as the importer names them: every
// "...Texture" object with an "index", extras excepted) and the UV sets they read.
void renumber(json& node, const std::function<int(int)>& global, const std::function<int(int)>& uv) {
  if (node.is_array())
    for (json& e : node) renumber(e, global, uv);
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (it.key() == "extras") continue;
    if (is_texture_info(it.key(), *it)) {
      (*it)["index"] = global((*it)["index"].get<int>());
      renumber_tex_coords(*it, uv);
    }
    renumber(*it, global, uv);
  }
}

class Writer {
public:
  Writer(const std::vector<int>& uv_sets, BufferWriter& buf, tinygltf::Model& model)
      : uv_sets_(uv_sets), buf_(buf), model_(model) {}

  int image(const std::shared_ptr<const Image>& shared) {
    if (auto it = by_pointer_.find(shared.get()); it != by_pointer_.end()) return it->second;
    const Image& img = *shared;
    const size_t h = std::hash<std::string_view>()(
        std::string_view(reinterpret_cast<const char*>(img.data.data()), img.data.size()));
    for (int i : images_[h])
      if (model_.images[i].mimeType == img.mime_type && *image_bytes_[i] == img.data) return by_pointer_[&img] = i;
    // Inside the file (a buffer view), so that the LOD carries its textures wherever it goes.
    tinygltf::Image gi;
    gi.name = printable_text(img.name);  // a file name from the input: glTF's JSON must be UTF-8
    gi.mimeType = img.mime_type;
    gi.bufferView = buf_.add_view(img.data);
    model_.images.push_back(gi);
    const int i = int(model_.images.size()) - 1;
    images_[h].push_back(i);
    image_bytes_[i] = &img.data;
    return by_pointer_[&img] = i;
  }

  int sampler(const std::string& text) {
    if (text.empty()) return -1;
    if (auto it = samplers_.find(text); it != samplers_.end()) return it->second;
    const json j = json::parse(text);
    tinygltf::Sampler s;
    s.name = printable_text(j.value("name", ""));
    s.magFilter = j.value("magFilter", -1);
    s.minFilter = j.value("minFilter", -1);
    s.wrapS = j.value("wrapS", TINYGLTF_TEXTURE_WRAP_REPEAT);
    s.wrapT = j.value("wrapT", TINYGLTF_TEXTURE_WRAP_REPEAT);
    extensions_and_extras(j, s);
    model_.samplers.push_back(s);
    return samplers_[text] = int(model_.samplers.size()) - 1;
  }

  int texture(const Texture& tex) {
    json j = json::parse(tex.gltf);
    auto source = [&](json& s) {
      if (s.is_number_integer() && s.get<int>() >= 0 && size_t(s.get<int>()) < tex.images.size())
        s = image(tex.images[s.get<size_t>()]);
    };
    if (j.contains("source")) source(j["source"]);
    if (j.contains("extensions") && j["extensions"].is_object())
      for (auto& [name, ext] : j["extensions"].items())
        if (ext.is_object() && ext.contains("source")) source(ext["source"]);
    const int s = sampler(tex.sampler);
    const std::string key = j.dump() + "#" + std::to_string(s);
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    tinygltf::Texture gt;
    gt.name = printable_text(j.value("name", ""));
    gt.source = j.value("source", -1);
    gt.sampler = s;
    extensions_and_extras(j, gt);
    model_.textures.push_back(gt);
    return textures_[key] = int(model_.textures.size()) - 1;
  }

  void material(const Material& m) {
    tinygltf::Material gm;
    gm.name = m.name;
    gm.pbrMetallicRoughness.baseColorFactor = {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]};
    if (m.gltf.empty()) {
      gm.pbrMetallicRoughness.metallicFactor = 0.0;  // a plain colour, as generated meshes have them
      model_.materials.push_back(gm);
      return;
    }
    json g = json::parse(m.gltf);
    std::vector<int> global(m.textures.size(), -2);
    renumber(
        g,
        [&](int local) {
          if (local < 0 || size_t(local) >= m.textures.size()) return -1;
          if (global[local] == -2) global[local] = texture(m.textures[local]);
          return global[local];
        },
        [&](int set) { return written_uv_index(uv_sets_, set); });
    const json pbr = g.contains("pbrMetallicRoughness") ? g["pbrMetallicRoughness"] : json::object();
    auto& p = gm.pbrMetallicRoughness;
    p.metallicFactor = pbr.value("metallicFactor", 1.0);
    p.roughnessFactor = pbr.value("roughnessFactor", 1.0);
    if (pbr.contains("baseColorTexture")) texture_info(pbr["baseColorTexture"], p.baseColorTexture);
    if (pbr.contains("metallicRoughnessTexture"))
      texture_info(pbr["metallicRoughnessTexture"], p.metallicRoughnessTexture);
    extensions_and_extras(pbr, p);
    if (g.contains("normalTexture")) {
      texture_info(g["normalTexture"], gm.normalTexture);
      gm.normalTexture.scale = g["normalTexture"].value("scale", 1.0);
    }
    if (g.contains("occlusionTexture")) {
      texture_info(g["occlusionTexture"], gm.occlusionTexture);
      gm.occlusionTexture.strength = g["occlusionTexture"].value("strength", 1.0);
    }
    if (g.contains("emissiveTexture")) texture_info(g["emissiveTexture"], gm.emissiveTexture);
    gm.emissiveFactor = numbers(g.value("emissiveFactor", json()), {0.0, 0.0, 0.0});
    gm.alphaMode = g.value("alphaMode", "OPAQUE");
    gm.alphaCutoff = g.value("alphaCutoff", 0.5);
    gm.doubleSided = g.value("doubleSided", false);
    extensions_and_extras(g, gm);
    model_.materials.push_back(gm);

    std::set<std::string> used;
    gltf_extension_names(m.gltf, used);
    for (const Texture& t : m.textures) {
      gltf_extension_names(t.gltf, used);
      gltf_extension_names(t.sampler, used);
    }
    for (const std::string& e : used) declare(model_.extensionsUsed, e);
    for (const std::string& e : m.required_extensions) {
      declare(model_.extensionsUsed, e);
      declare(model_.extensionsRequired, e);
    }
  }

private:
  static void declare(std::vector<std::string>& list, const std::string& e) {
    if (std::find(list.begin(), list.end(), e) == list.end()) list.push_back(e);
  }

  const std::vector<int>& uv_sets_;
  BufferWriter& buf_;
  tinygltf::Model& model_;
  std::unordered_map<size_t, std::vector<int>> images_;  // hash of the bytes -> images
  std::map<int, const std::vector<unsigned char>*> image_bytes_;
  std::map<const Image*, int> by_pointer_;  // the materials' own sharing, checked first
  std::map<std::string, int> samplers_, textures_;
};

}  // namespace

void write_materials(const std::vector<Material>& mats, const std::vector<int>& uv_sets, BufferWriter& buf,
                     tinygltf::Model& model) {
  Writer w(uv_sets, buf, model);
  for (const Material& m : mats) w.material(m);
}

int tangent_uv_set(const Material& m) {
  if (!needs_tangent_space(m)) return -1;
  json g = json::parse(m.gltf, nullptr, false);
  if (g.is_discarded()) return -1;
  if (is_texture_info("normalTexture", g.value("normalTexture", json()))) return tex_coord(g["normalTexture"]);
  if (!g.contains("extensions") || !g["extensions"].is_object()) return 0;
  for (auto& [name, ext] : g["extensions"].items()) {
    if (!ext.is_object()) continue;
    for (auto& [key, info] : ext.items())
      if (key.size() > 13 && key.compare(key.size() - 13, 13, "NormalTexture") == 0 && is_texture_info(key, info))
        return tex_coord(info);
  }
  const json& aniso = g["extensions"].value("KHR_materials_anisotropy", json());
  if (aniso.is_object() && is_texture_info("anisotropyTexture", aniso.value("anisotropyTexture", json())))
    return tex_coord(aniso["anisotropyTexture"]);
  return 0;
}

}  // namespace OpenMeshSkinned::detail
