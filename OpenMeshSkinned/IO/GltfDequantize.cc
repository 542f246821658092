#include "OpenMeshSkinned/IO/GltfDequantize.hh"

#include "OpenMeshSkinned/IO/GltfAccessors.hh"
#include "OpenMeshSkinned/IO/GltfJson.hh"

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

namespace {

// A quantised TEXCOORD accessor and the (material, set) of a primitive that reads it.
using QuantizedUv = std::pair<size_t, std::pair<size_t, size_t>>;

// KHR_texture_transform on every texture of a material that reads set \p set, when they all carry the
// same one with neither rotation nor a texCoord override: the affine map gltfpack adds to dequantise.
bool common_uv_transform(json& material, size_t set, double offset[2], double scale[2]) {
  std::vector<json*> infos;
  std::function<void(json&, const std::string&)> walk = [&](json& j, const std::string& key) {
    if (j.is_object()) {
      if (key.size() >= 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && j.contains("index") &&
          j.value("texCoord", size_t(0)) == set)
        infos.push_back(&j);
      for (auto& [k, v] : j.items()) walk(v, k);
    } else if (j.is_array()) {
      for (auto& v : j) walk(v, key);
    }
  };
  walk(material, "");
  if (infos.empty()) return false;
  json first;
  for (json* info : infos) {
    if (!info->contains("extensions") || !(*info)["extensions"].contains("KHR_texture_transform")) return false;
    const json& t = (*info)["extensions"]["KHR_texture_transform"];
    if (t.value("rotation", 0.0) != 0.0 || t.contains("texCoord")) return false;
    if (first.is_null()) first = t;
    if (t != first) return false;
  }
  const json o = first.value("offset", json::array({0.0, 0.0})), s = first.value("scale", json::array({1.0, 1.0}));
  if (!o.is_array() || o.size() != 2 || !s.is_array() || s.size() != 2) return false;
  for (int c = 0; c < 2; ++c) offset[c] = o[c].get<double>(), scale[c] = s[c].get<double>();
  for (json* info : infos) erase_extension(*info, "KHR_texture_transform");
  return true;
}

// The integer accessors that become floats, and which of them are texture coordinates of a material.
std::set<size_t> integer_accessors(json& doc, std::vector<QuantizedUv>& quantized_uvs) {
  const size_t n_accessors = doc["accessors"].size();
  std::set<size_t> to_float;
  auto consider = [&](const json& ref) {
    if (ref.is_number_unsigned() && ref.get<size_t>() < n_accessors &&
        doc["accessors"][ref.get<size_t>()].value("componentType", kFloat) != kFloat)
      to_float.insert(ref.get<size_t>());
  };
  const json meshes = doc.value("meshes", json::array()), animations = doc.value("animations", json::array());
  for (const auto& mesh : meshes)
    for (const auto& prim : mesh.value("primitives", json::array())) {
      const json attributes = prim.value("attributes", json::object()), targets = prim.value("targets", json::array());
      for (const auto& [name, ref] : attributes.items()) {
        if (name.rfind("JOINTS_", 0) == 0) continue;  // integers by definition
        consider(ref);
        if (name.rfind("TEXCOORD_", 0) == 0 && to_float.count(ref.get<size_t>()) && prim.contains("material"))
          quantized_uvs.push_back({ref.get<size_t>(), {prim["material"].get<size_t>(), std::stoul(name.substr(9))}});
      }
      for (const auto& target : targets)
        for (const auto& [name, ref] : target.items()) consider(ref);
    }
  for (const auto& anim : animations)
    for (const auto& sampler : anim.value("samplers", json::array()))
      if (sampler.contains("output")) consider(sampler["output"]);
  return to_float;
}

// The accessor meshes refer to is rewritten, so each (material, set) with a transform is folded into the
// accessor of its primitives once; primitives of two materials sharing coordinates get a copy each.
void fold_uv_transforms(json& doc, const std::vector<QuantizedUv>& quantized_uvs, GltfBytes& bytes,
                        const std::string& shown_as) {
  std::map<std::pair<size_t, size_t>, std::pair<std::vector<double>, std::vector<double>>> folded;
  std::map<size_t, std::pair<size_t, size_t>> accessor_owner;
  if (quantized_uvs.empty() || !doc.contains("materials") || !doc["materials"].is_array()) return;
  auto& materials = doc["materials"];
  for (auto& mesh : doc["meshes"])
    for (auto& prim : mesh["primitives"]) {
      if (!prim.contains("material") || !prim["material"].is_number_unsigned()) continue;
      const size_t mat = prim["material"].get<size_t>();
      if (mat >= materials.size()) continue;
      for (auto& [name, ref] : prim["attributes"].items()) {
        if (name.rfind("TEXCOORD_", 0) != 0) continue;
        const size_t set = std::stoul(name.substr(9)), a = ref.get<size_t>();
        if (std::find(quantized_uvs.begin(), quantized_uvs.end(), std::make_pair(a, std::make_pair(mat, set))) ==
            quantized_uvs.end())
          continue;
        const auto key = std::make_pair(mat, set);
        if (!folded.count(key)) {
          double o[2], s[2];
          if (!common_uv_transform(materials[mat], set, o, s)) continue;
          folded[key] = {{o[0], o[1]}, {s[0], s[1]}};
        }
        auto owner = accessor_owner.find(a);
        if (owner != accessor_owner.end() && owner->second == key) continue;  // already folded
        size_t target = a;
        if (owner != accessor_owner.end()) {
          doc["accessors"].push_back(doc["accessors"][a]);
          target = doc["accessors"].size() - 1;
          ref = target;
        }
        std::vector<double> uv = accessor_values(doc, target, bytes, shown_as);
        const auto& [o, s] = folded[key];
        for (size_t i = 0; i < uv.size(); ++i) uv[i] = o[i % 2] + s[i % 2] * uv[i];
        write_float_accessor(doc, target, uv, bytes);
        accessor_owner[target] = key;
      }
    }
  if (!folded.empty() && materials.dump().find("\"KHR_texture_transform\"") == std::string::npos)
    undeclare(doc, "KHR_texture_transform");
}

}  // namespace

bool dequantize(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("accessors") || !doc["accessors"].is_array()) return false;
  std::vector<QuantizedUv> quantized_uvs;
  const std::set<size_t> to_float = integer_accessors(doc, quantized_uvs);
  if (to_float.empty()) return false;
  for (size_t a : to_float) write_float_accessor(doc, a, accessor_values(doc, a, bytes, shown_as), bytes);
  fold_uv_transforms(doc, quantized_uvs, bytes, shown_as);
  return true;
}

}  // namespace OpenMeshSkinned::detail
