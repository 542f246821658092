#include "OpenMeshSkinned/IO/GltfMaterials.hh"

#include "OpenMeshSkinned/IO/GltfResources.hh"
#include "OpenMeshSkinned/IO/Textures.hh"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>

namespace OpenMeshSkinned {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

bool is_texture_info(const std::string& key, const json& v) {
  return key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && v.is_object() && v.contains("index") &&
         v["index"].is_number_integer();
}

// Calls \p f on every texture reference of a material (the core ones and those of its extensions: every
// "...Texture" object with an "index"); a reference \p f returns false for is removed. Extras are the
// author's own data and are left as they are.
void each_texture_info(json& node, const std::function<bool(json&, const std::string&)>& f) {
  if (node.is_array()) {
    for (json& e : node) each_texture_info(e, f);
    return;
  }
  if (!node.is_object()) return;
  std::vector<std::string> drop;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (it.key() == "extras") continue;
    if (is_texture_info(it.key(), *it) && !f(*it, it.key())) {
      drop.push_back(it.key());
      continue;
    }
    each_texture_info(*it, f);
  }
  for (const auto& k : drop) node.erase(k);
}

void extension_names(const json& node, std::set<std::string>& names) {
  if (node.is_array())
    for (const json& e : node) extension_names(e, names);
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (it.key() == "extras") continue;
    if (it.key() == "extensions" && it->is_object())
      for (auto e = it->begin(); e != it->end(); ++e) names.insert(e.key());
    extension_names(*it, names);
  }
}

// See read_gltf_materials(): the materials in the order assimp 5.2's lazy glTF reader loads them.
std::vector<int> reader_material_order(const json& doc) {
  const json none = json::array();
  auto array = [&](const json& j, const char* key) -> const json& {
    return j.is_object() && j.contains(key) && j[key].is_array() ? j[key] : none;
  };
  const json& nodes = array(doc, "nodes");
  const json& meshes = array(doc, "meshes");
  std::vector<char> node_seen(nodes.size()), mesh_seen(meshes.size()), material_seen(array(doc, "materials").size());
  std::vector<int> order;
  auto index = [](const json& j, size_t n) {
    return j.is_number_integer() && j.get<int64_t>() >= 0 && size_t(j.get<int64_t>()) < n ? int(j.get<int64_t>()) : -1;
  };
  std::function<void(const json&)> node = [&](const json& ref) {
    const int n = index(ref, nodes.size());
    if (n < 0 || node_seen[n]) return;
    node_seen[n] = 1;
    for (const json& c : array(nodes[n], "children")) node(c);
    const int m = nodes[n].is_object() && nodes[n].contains("mesh") ? index(nodes[n]["mesh"], meshes.size()) : -1;
    if (m < 0 || mesh_seen[m]) return;
    mesh_seen[m] = 1;
    for (const json& prim : array(meshes[m], "primitives")) {
      const int mat =
          prim.is_object() && prim.contains("material") ? index(prim["material"], material_seen.size()) : -1;
      if (mat >= 0 && !material_seen[mat]) material_seen[mat] = 1, order.push_back(mat);
    }
  };
  const json& scenes = array(doc, "scenes");
  const int scene = doc.contains("scene") ? index(doc["scene"], scenes.size()) : scenes.empty() ? -1 : 0;
  if (scene >= 0)
    for (const json& n : array(scenes[scene], "nodes")) node(n);
  for (const json& skin : array(doc, "skins"))
    for (const json& j : array(skin, "joints")) node(j);
  for (const json& anim : array(doc, "animations"))
    for (const json& ch : array(anim, "channels"))
      if (ch.is_object() && ch.contains("target") && ch["target"].is_object() && ch["target"].contains("node"))
        node(ch["target"]["node"]);
  return order;
}

// The file's materials one by one, each with its own copy of the textures it uses; a texture that cannot be
// kept is remembered with the materials kept without it, for one warning line each.
class FileMaterials {
public:
  FileMaterials(const json& doc, std::vector<unsigned char> bin, std::string source_dir)
      : res_(doc, std::move(bin), std::move(source_dir)),
        textures_(doc.contains("textures") ? doc["textures"] : none_),
        samplers_(doc.contains("samplers") ? doc["samplers"] : none_) {
    if (doc.contains("extensionsRequired"))
      for (const json& e : doc["extensionsRequired"])
        if (e.is_string()) required_.insert(e.get<std::string>());
  }

  // Material \p mi, the object \p m as the file has it: its name and base colour factor taken out, its
  // texture references renumbered into its own textures.
  Material material(size_t mi, json m) {
    Material mat;
    if (m.contains("name") && m["name"].is_string()) mat.name = m["name"];
    m.erase("name");
    if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object()) {
      json& pbr = m["pbrMetallicRoughness"];
      if (pbr.contains("baseColorFactor") && pbr["baseColorFactor"].is_array() && pbr["baseColorFactor"].size() == 4) {
        for (int c = 0; c < 4; ++c) mat.base_color[c] = pbr["baseColorFactor"][c].get<double>();
        pbr.erase("baseColorFactor");
      }
    }
    std::map<int, int> local;  // the file's texture -> this material's
    each_texture_info(m, [&](json& info, const std::string&) {
      const int t = info["index"];
      auto it = local.find(t);
      if (it == local.end()) {
        Texture tex;
        const bool ok = texture(t, tex);
        it = local.emplace(t, ok ? int(mat.textures.size()) : -1).first;
        if (ok) mat.textures.push_back(std::move(tex));
      }
      if (it->second < 0) {
        const std::string who = mat.name.empty() ? "#" + std::to_string(mi) : mat.name;
        if (lost_[t].second.empty() || lost_[t].second.back() != who) lost_[t].second.push_back(who);
        return false;
      }
      info["index"] = it->second;
      return true;
    });
    if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object()) {
      const json& pbr = m["pbrMetallicRoughness"];
      // Only a reference each_texture_info() renumbered points into mat.textures (a malformed one, an
      // index that is no integer, is left as it was and names no texture here).
      if (pbr.contains("baseColorTexture") && is_texture_info("baseColorTexture", pbr["baseColorTexture"])) {
        const auto t = pbr["baseColorTexture"]["index"].get<long long>();
        if (t >= 0 && size_t(t) < mat.textures.size()) {
          const Texture& bt = mat.textures[size_t(t)];
          mat.base_color_texture = bt.images.empty() ? "texture" : bt.images.front()->name;
        }
      }
      if (pbr.empty()) m.erase("pbrMetallicRoughness");
    }
    std::set<std::string> used;
    extension_names(m, used);
    for (const Texture& tex : mat.textures) {
      gltf_extension_names(tex.gltf, used);
      gltf_extension_names(tex.sampler, used);
    }
    for (const std::string& e : used)
      if (required_.count(e)) mat.required_extensions.push_back(e);
    mat.gltf = m.dump();
    return mat;
  }

  // One line per texture that could not be kept, naming the materials kept without it.
  void report_lost(std::vector<std::string>& warnings) const {
    for (const auto& [t, why] : lost_) {
      std::string names;
      for (const auto& n : why.second) names += (names.empty() ? "\"" : ", \"") + n + "\"";
      warnings.push_back(why.first + ": material" + (why.second.size() > 1 ? "s " : " ") + names + " kept without it");
    }
  }

private:
  // The file's texture \p t with its sampler and its images (the core "source" and those of image extensions:
  // KHR_texture_basisu, EXT_texture_webp, ...) renumbered into the texture's own; false (and remembered as
  // lost) when it cannot be read.
  bool texture(int t, Texture& tex) {
    std::string problem;
    bool ok = t >= 0 && size_t(t) < textures_.size() && textures_[size_t(t)].is_object();
    if (!ok) problem = "does not exist";
    json tj = ok ? textures_[size_t(t)] : json::object();
    if (ok && tj.contains("sampler")) {
      const json& s = tj["sampler"];
      if (s.is_number_integer() && s.get<int>() >= 0 && size_t(s.get<int>()) < samplers_.size())
        tex.sampler = samplers_[s.get<size_t>()].dump();
      tj.erase("sampler");
    }
    std::vector<json*> sources;
    if (tj.contains("source")) sources.push_back(&tj["source"]);
    if (tj.contains("extensions") && tj["extensions"].is_object())
      for (auto& [name, ext] : tj["extensions"].items())
        if (ext.is_object() && ext.contains("source")) sources.push_back(&ext["source"]);
    std::map<int, int> image_local;
    for (json* src : sources) {
      if (!ok) break;
      const int i = src->is_number_integer() ? src->get<int>() : -1;
      if (!image_local.count(i)) {
        std::shared_ptr<const Image> img;
        if (!(ok = res_.image(i, img, problem))) break;
        image_local[i] = int(tex.images.size());
        tex.images.push_back(std::move(img));
      }
      *src = image_local[i];
    }
    tex.gltf = tj.dump();
    if (!ok) {
      const std::string what =
          "texture " + std::to_string(t) +
          (tj.contains("name") && tj["name"].is_string() ? " (\"" + tj["name"].get<std::string>() + "\")"
                                                         : std::string());
      lost_[t].first = what + " " + problem;
    }
    return ok;
  }

  const json none_ = json::array();
  GltfResources res_;
  const json& textures_;
  const json& samplers_;
  std::set<std::string> required_;
  std::map<int, std::pair<std::string, std::vector<std::string>>> lost_;
};

}  // namespace

void gltf_extension_names(const std::string& json_text, std::set<std::string>& names) {
  if (json_text.empty()) return;
  const json j = json::parse(json_text, nullptr, false);
  if (!j.is_discarded()) extension_names(j, names);
}

bool needs_tangent_space(const Material& m) {
  if (m.gltf.empty()) return false;
  json g = json::parse(m.gltf, nullptr, false);
  if (g.is_discarded()) return false;
  bool needs =
      g.contains("extensions") && g["extensions"].is_object() && g["extensions"].contains("KHR_materials_anisotropy");
  each_texture_info(g, [&](json&, const std::string& key) {
    needs |= key == "normalTexture" || (key.size() > 13 && key.compare(key.size() - 13, 13, "NormalTexture") == 0);
    return true;
  });
  return needs;
}

bool read_gltf_materials(const std::string& read_path, const std::string& source, std::vector<Material>& out,
                         std::vector<int>& reader_order, std::vector<std::string>& warnings) {
  json doc;
  std::vector<unsigned char> bin;
  if (!load_gltf_document(read_path, doc, bin)) return false;
  try {
    FileMaterials file(doc, std::move(bin), fs::absolute(fs::path(source)).parent_path().string());
    const json none = json::array();
    const json& materials = doc.contains("materials") ? doc["materials"] : none;
    std::vector<Material> result;
    for (size_t mi = 0; mi < materials.size(); ++mi)
      result.push_back(file.material(mi, materials[mi].is_object() ? materials[mi] : json::object()));
    file.report_lost(warnings);
    out = std::move(result);
    reader_order = reader_material_order(doc);
    return true;
  } catch (const json::exception& e) {
    warnings.push_back("the file's materials cannot be read as glTF (" + std::string(e.what()) +
                       "): kept as the reader reports them");
    return false;
  }
}

}  // namespace OpenMeshSkinned
