#include "OpenMeshSkinned/IO/GltfDecompress.hh"

#include "OpenMeshSkinned/IO/DracoDecode.hh"
#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/GltfDequantize.hh"
#include "OpenMeshSkinned/IO/GltfInterpolation.hh"
#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/MeshoptDecode.hh"

#include <fstream>
#include <iterator>
#include <set>

namespace OpenMeshSkinned::detail {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const char* const kQuantization = "KHR_mesh_quantization";

// Required extensions the tool honours: the ones decoded here, and the ones that only change how a
// texture is stored or shaded (kept with the materials, or ignored by the geometry).
bool honoured(const std::string& ext) {
  static const std::set<std::string> known = {kMeshoptExtensions[0],  kMeshoptExtensions[1], kDracoExtension,
                                              kQuantization,          "KHR_texture_basisu",  "EXT_texture_webp",
                                              "KHR_texture_transform"};
  return known.count(ext) || ext.rfind("KHR_materials_", 0) == 0;
}

}  // namespace

void check_required_extensions(const json& doc, const std::string& shown_as) {
  if (!doc.contains("extensionsRequired") || !doc["extensionsRequired"].is_array()) return;
  for (const auto& e : doc["extensionsRequired"]) {
    const std::string name = e.is_string() ? e.get<std::string>() : e.dump();
    if (!honoured(name))
      throw IOError(shown_as + ": requires the glTF extension " + name + ", which this tool cannot read");
  }
}

std::vector<std::string> decompress_gltf(json& doc, GltfBytes& bytes, const std::string& shown_as,
                                         std::vector<std::string>& notes) {
  std::vector<std::string> done;
  const bool meshopt = decode_meshopt(doc, bytes, shown_as);
  if (meshopt) {
    for (const char* ext : kMeshoptExtensions)
      if (declared(doc, ext)) done.push_back(ext), undeclare(doc, ext);
  }
  if (decode_draco(doc, bytes, shown_as)) done.push_back(kDracoExtension);
  undeclare(doc, kDracoExtension);
  if (dequantize(doc, bytes, shown_as) || declared(doc, kQuantization)) {
    if (declared(doc, kQuantization)) done.push_back(kQuantization);
    undeclare(doc, kQuantization);
  }
  // After the decoders (animation data is often compressed or quantised).
  const std::vector<std::string> rewritten = linearize_samplers(doc, bytes, shown_as);
  if (!rewritten.empty()) done.push_back("STEP or CUBICSPLINE animation samplers");
  notes.insert(notes.end(), rewritten.begin(), rewritten.end());
  // Last: it renumbers the buffers, which \p bytes knows by their numbers until every view is decoded.
  if (meshopt) drop_fallback_buffers(doc);
  return done;
}

}  // namespace OpenMeshSkinned::detail
