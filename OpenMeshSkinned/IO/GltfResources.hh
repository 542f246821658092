#pragma once
/** \file GltfResources.hh
 *  A glTF 2.0 file read for its materials: its JSON and binary chunk, and the images its textures name
 *  (from a buffer view, a data URI or a file beside the source), each read once however many materials
 *  use it. Internal to the glTF material reader (GltfMaterials.cc).
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** The JSON of the .gltf or .glb \p path into \p doc and a GLB's binary chunk into \p bin; false when the
 *  file is not glTF 2.0 (by its extension, its GLB header or its asset version) or its JSON does not parse. */
bool load_gltf_document(const std::string& path, nlohmann::json& doc, std::vector<unsigned char>& bin);

class GltfResources {
public:
  /// \p doc must outlive this; \p bin is its GLB chunk (empty for a .gltf); files are looked for in \p source_dir.
  GltfResources(const nlohmann::json& doc, std::vector<unsigned char> bin, std::string source_dir);

  /** Image \p i of the document, as glTF may carry it (PNG, JPEG, KTX2 and WebP byte for byte; other formats
   *  re-encoded as PNG). False with \p problem set (the same each time it is asked) when it cannot be read. */
  bool image(int i, std::shared_ptr<const Image>& out, std::string& problem);

private:
  struct Entry {
    bool ok = false;
    std::shared_ptr<const Image> image;
    std::string problem;
  };

  const nlohmann::json* at(const char* kind, int i) const;
  bool buffer(int b, const std::vector<unsigned char>*& out, std::string& problem);
  bool read_image(int i, Image& out, std::string& problem);

  const nlohmann::json& doc_;
  const std::vector<unsigned char> bin_;
  const std::string dir_;
  std::map<int, std::vector<unsigned char>> buffers_;
  std::map<int, Entry> images_;
};

}  // namespace OpenMeshSkinned
