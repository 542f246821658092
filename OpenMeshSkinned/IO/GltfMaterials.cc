#include "OpenMeshSkinned/IO/GltfMaterials.hh"

#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/Textures.hh"

#include <cereal/external/base64.hpp>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>

namespace OpenMeshSkinned {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The JSON of a .gltf or .glb and a GLB's binary chunk; false when the file is not glTF 2.0.
bool load_document(const std::string& path, json& doc, std::vector<unsigned char>& bin) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".gltf" && ext != ".glb") return false;
  std::string data;
  detail::read_file_bytes(path, data);
  if (data.size() >= 20 && data.compare(0, 4, "glTF") == 0) {
    detail::GlbChunks chunks;
    if (!detail::split_glb(data, chunks)) return false;
    doc = json::parse(chunks.json, nullptr, false);
    bin.assign(chunks.bin.begin(), chunks.bin.end());
  } else {
    doc = json::parse(data, nullptr, false);
  }
  if (doc.is_discarded() || !doc.is_object()) return false;
  const json* version = doc.contains("asset") && doc["asset"].is_object() && doc["asset"].contains("version")
                            ? &doc["asset"]["version"]
                            : nullptr;
  return version && version->is_string() && version->get<std::string>().rfind("2", 0) == 0;
}

// The bytes of a "data:" URI; false when it is not one.
bool data_uri(const std::string& uri, std::vector<unsigned char>& bytes) {
  if (uri.rfind("data:", 0) != 0) return false;
  const size_t comma = uri.find(',');
  if (comma == std::string::npos) return false;
  const std::string head = uri.substr(0, comma), payload = uri.substr(comma + 1);
  const std::string raw = head.size() >= 7 && head.compare(head.size() - 7, 7, ";base64") == 0
                              ? cereal::base64::decode(payload)
                              : detail::percent_decoded(payload);
  bytes.assign(raw.begin(), raw.end());
  return true;
}

// The file's buffers and images, each read once however many materials use it.
class Resources {
public:
  Resources(const json& doc, std::vector<unsigned char> bin, std::string source_dir)
      : doc_(doc), bin_(std::move(bin)), dir_(std::move(source_dir)) {}

  bool image(int i, std::shared_ptr<const Image>& out, std::string& problem) {
    auto it = images_.find(i);
    if (it == images_.end()) {
      Entry e;
      Image img;
      e.ok = read_image(i, img, e.problem);
      e.image = std::make_shared<const Image>(std::move(img));
      it = images_.emplace(i, std::move(e)).first;
    }
    out = it->second.image;
    problem = it->second.problem;
    return it->second.ok;
  }

private:
  struct Entry {
    bool ok = false;
    std::shared_ptr<const Image> image;
    std::string problem;
  };

  const json* at(const char* kind, int i) const {
    if (!doc_.contains(kind) || !doc_[kind].is_array() || i < 0 || size_t(i) >= doc_[kind].size()) return nullptr;
    return doc_[kind][size_t(i)].is_object() ? &doc_[kind][size_t(i)] : nullptr;
  }

  bool buffer(int b, const std::vector<unsigned char>*& out, std::string& problem) {
    auto it = buffers_.find(b);
    if (it != buffers_.end()) {
      out = &it->second;
      return true;
    }
    const json* buf = at("buffers", b);
    if (!buf) {
      problem = "its buffer " + std::to_string(b) + " does not exist";
      return false;
    }
    std::vector<unsigned char> bytes;
    if (!buf->contains("uri")) {
      if (b != 0 || bin_.empty()) {  // only a GLB's first buffer is its binary chunk
        problem = "its buffer " + std::to_string(b) + " has no data";
        return false;
      }
      out = &bin_;
      return true;
    }
    const std::string uri = buf->value("uri", "");
    std::string name;
    if (!data_uri(uri, bytes) && !find_texture_file(detail::percent_decoded(uri), dir_, bytes, name, problem)) {
      problem = "its buffer \"" + uri + "\" is " + problem;
      return false;
    }
    out = &(buffers_[b] = std::move(bytes));
    return true;
  }

  bool read_image(int i, Image& out, std::string& problem) {
    const json* img = at("images", i);
    if (!img) {
      problem = "its image " + std::to_string(i) + " does not exist";
      return false;
    }
    std::vector<unsigned char> bytes;
    std::string name = img->contains("name") && (*img)["name"].is_string() ? (*img)["name"].get<std::string>() : "";
    if (img->contains("bufferView")) {
      const json* view =
          at("bufferViews", (*img)["bufferView"].is_number_integer() ? (*img)["bufferView"].get<int>() : -1);
      const std::vector<unsigned char>* data = nullptr;
      if (!view) {
        problem = "its image's buffer view does not exist";
        return false;
      }
      if (!buffer(view->value("buffer", -1), data, problem)) return false;
      const size_t off = view->value("byteOffset", size_t(0)), len = view->value("byteLength", size_t(0));
      if (off > data->size() || len > data->size() - off || len == 0) {
        problem = "its image's buffer view lies outside its buffer";
        return false;
      }
      bytes.assign(data->begin() + off, data->begin() + off + len);
    } else if (img->contains("uri") && (*img)["uri"].is_string()) {
      const std::string uri = (*img)["uri"];
      std::string file_name;
      if (!data_uri(uri, bytes)) {
        if (!find_texture_file(detail::percent_decoded(uri), dir_, bytes, file_name, problem)) {
          problem = "image \"" + uri + "\" " + problem;
          return false;
        }
        if (name.empty()) name = file_name;
      }
    } else {
      problem = "its image " + std::to_string(i) + " has neither a uri nor a buffer view";
      return false;
    }
    if (name.empty()) name = "image" + std::to_string(i);
    out.name = name;
    out.mime_type = gltf_mime_type(bytes);
    if (const std::string cut = image_stream_problem(bytes); !cut.empty()) {
      problem = "its image " + std::to_string(i) + " is " + cut;
      return false;
    }
    if (!out.mime_type.empty()) {
      out.data = std::move(bytes);  // as it is, byte for byte
      return true;
    }
    // Not a format glTF allows (a BMP or TGA some exporters refer to): made PNG, as for other formats.
    return encode_for_gltf(bytes, name, out, problem);
  }

  const json& doc_;
  const std::vector<unsigned char> bin_;
  const std::string dir_;
  std::map<int, std::vector<unsigned char>> buffers_;
  std::map<int, Entry> images_;
};

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
  if (!load_document(read_path, doc, bin)) return false;
  try {
    std::set<std::string> required;
    if (doc.contains("extensionsRequired"))
      for (const json& e : doc["extensionsRequired"])
        if (e.is_string()) required.insert(e.get<std::string>());
    Resources res(doc, std::move(bin), fs::absolute(fs::path(source)).parent_path().string());
    const json none = json::array();
    const json& materials = doc.contains("materials") ? doc["materials"] : none;
    const json& textures = doc.contains("textures") ? doc["textures"] : none;
    const json& samplers = doc.contains("samplers") ? doc["samplers"] : none;

    // A texture that cannot be kept: why, and the materials kept without it (one warning line each).
    std::map<int, std::pair<std::string, std::vector<std::string>>> lost;
    std::vector<Material> result;
    for (size_t mi = 0; mi < materials.size(); ++mi) {
      json m = materials[mi].is_object() ? materials[mi] : json::object();
      Material mat;
      if (m.contains("name") && m["name"].is_string()) mat.name = m["name"];
      m.erase("name");
      if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object()) {
        json& pbr = m["pbrMetallicRoughness"];
        if (pbr.contains("baseColorFactor") && pbr["baseColorFactor"].is_array() &&
            pbr["baseColorFactor"].size() == 4) {
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
          std::string problem;
          bool ok = t >= 0 && size_t(t) < textures.size() && textures[size_t(t)].is_object();
          if (!ok) problem = "does not exist";
          json tj = ok ? textures[size_t(t)] : json::object();
          if (ok && tj.contains("sampler")) {
            const json& s = tj["sampler"];
            if (s.is_number_integer() && s.get<int>() >= 0 && size_t(s.get<int>()) < samplers.size())
              tex.sampler = samplers[s.get<size_t>()].dump();
            tj.erase("sampler");
          }
          // The core "source" and those of image extensions (KHR_texture_basisu, EXT_texture_webp, ...).
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
              if (!(ok = res.image(i, img, problem))) break;
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
            lost[t].first = what + " " + problem;
            it = local.emplace(t, -1).first;
          } else {
            it = local.emplace(t, int(mat.textures.size())).first;
            mat.textures.push_back(std::move(tex));
          }
        }
        if (it->second < 0) {
          const std::string who = mat.name.empty() ? "#" + std::to_string(mi) : mat.name;
          if (lost[t].second.empty() || lost[t].second.back() != who) lost[t].second.push_back(who);
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
        if (required.count(e)) mat.required_extensions.push_back(e);
      mat.gltf = m.dump();
      result.push_back(std::move(mat));
    }
    for (const auto& [t, why] : lost) {
      std::string names;
      for (const auto& n : why.second) names += (names.empty() ? "\"" : ", \"") + n + "\"";
      warnings.push_back(why.first + ": material" + (why.second.size() > 1 ? "s " : " ") + names + " kept without it");
    }
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
