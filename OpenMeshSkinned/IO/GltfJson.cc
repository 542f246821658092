#include "OpenMeshSkinned/IO/GltfJson.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <algorithm>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

void erase_extension(json& object, const std::string& name) {
  if (!object.contains("extensions") || !object["extensions"].is_object()) return;
  object["extensions"].erase(name);
  if (object["extensions"].empty()) object.erase("extensions");
}

void undeclare(json& doc, const std::string& name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list) || !doc[list].is_array()) continue;
    auto& a = doc[list];
    a.erase(std::remove(a.begin(), a.end(), json(name)), a.end());
    if (a.empty()) doc.erase(list);
  }
}

bool declared(const json& doc, const std::string& name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (doc.contains(list) && doc[list].is_array())
      for (const auto& e : doc[list])
        if (e == name) return true;
  return false;
}

json& array_of(json& doc, const char* name) {
  if (!doc.contains(name) || !doc[name].is_array()) doc[name] = json::array();
  return doc[name];
}

size_t index_in(const json& object, const char* key, size_t size, const std::string& what) {
  if (!object.contains(key) || !object[key].is_number_unsigned() || object[key].get<size_t>() >= size)
    throw IOError(what + " has no valid \"" + key + "\"");
  return object[key].get<size_t>();
}

}  // namespace OpenMeshSkinned::detail
