#include "OpenMeshSkinned/IO/GltfMorphWeights.hh"

#include "OpenMeshSkinned/IO/GltfAccessors.hh"
#include "OpenMeshSkinned/IO/GltfBytes.hh"
#include "OpenMeshSkinned/IO/GltfResources.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

const SignedMorphWeights::Channel* SignedMorphWeights::find(size_t animation, const std::string& node) const {
  const auto it = channels.find({animation, node});
  return it == channels.end() ? nullptr : &it->second;
}

SignedMorphWeights read_signed_morph_weights(const std::string& read_path, std::vector<std::string>& warnings) {
  SignedMorphWeights out;
  json doc;
  std::vector<unsigned char> chunk;
  if (!load_gltf_document(read_path, doc, chunk)) return out;
  if (!doc.contains("animations") || !doc["animations"].is_array()) return out;
  std::string bin(chunk.begin(), chunk.end());
  GltfBytes bytes(doc, chunk.empty() ? nullptr : &bin, std::filesystem::absolute(read_path).parent_path(), read_path);
  try {
    const json nodes = doc.value("nodes", json::array());
    // assimp matches a weights channel to its mesh by the node's name: a name two nodes share is ambiguous,
    // and is left to assimp's (clamped) reading.
    std::vector<std::string> names(nodes.size());
    std::map<std::string, int> named;
    for (size_t n = 0; n < nodes.size(); ++n) {
      const std::string own = nodes[n].is_object() ? nodes[n].value("name", "") : "";
      names[n] = own.empty() ? "nodes[" + std::to_string(n) + "]" : own;
      ++named[names[n]];
    }
    const json& animations = doc["animations"];
    for (size_t a = 0; a < animations.size(); ++a) {
      const json samplers = animations[a].value("samplers", json::array());
      for (const json& ch : animations[a].value("channels", json::array())) {
        if (!ch.contains("target") || ch["target"].value("path", "") != "weights") continue;
        const long node = ch["target"].value("node", -1L), s = ch.value("sampler", -1L);
        if (node < 0 || size_t(node) >= nodes.size() || s < 0 || size_t(s) >= samplers.size()) continue;
        const json& sampler = samplers[size_t(s)];
        const std::vector<double> in = accessor_values(doc, sampler.at("input").get<size_t>(), bytes, read_path);
        std::vector<double> values = accessor_values(doc, sampler.at("output").get<size_t>(), bytes, read_path);
        if (in.empty() || values.size() % in.size() != 0) continue;
        if (std::none_of(values.begin(), values.end(), [](double w) { return w < 0.0; })) continue;
        const std::string& name = names[size_t(node)];
        if (named[name] > 1) continue;
        out.channels[{a, name}] = {in.size(), std::move(values)};
      }
    }
  } catch (const std::exception& e) {  // a field of the wrong type, data past its buffer
    warnings.push_back(std::string("the morph weights could not be read with their signs (") + e.what() +
                       "): negative weights are kept as 0");
    return {};
  }
  return out;
}

}  // namespace OpenMeshSkinned::detail
