#pragma once
/** \file GltfDecompress.hh
 *  Compressed and quantised glTF made plain before assimp 5.2 reads it. Internal to GltfRepair.
 *
 *  assimp 5.2 knows neither meshopt compression nor quantised attributes, and its Draco decoding fails on
 *  scenes with several Draco primitives. Decoding all three ourselves keeps one reading path:
 *  - `EXT_meshopt_compression` / `KHR_meshopt_compression` buffer views are decoded with Debian's
 *    meshoptimizer (0.18: vertex codec version 0, index codecs 0 and 1, the octahedral, quaternion and
 *    exponential filters) and their fallback buffers dropped;
 *  - `KHR_draco_mesh_compression` primitives are decoded with Debian's libdraco;
 *  - attributes stored as (normalised) integers (`KHR_mesh_quantization`) and integer animation outputs
 *    become floats with the values the spec gives them; the node transforms gltfpack adds to dequantise
 *    stay and keep working, and a `KHR_texture_transform` that only undoes a quantised `TEXCOORD` is
 *    folded into the coordinates (assimp would drop it).
 *  The decoded copy no longer declares these extensions.
 */

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

/// The bytes of a glTF's buffers, loaded when first asked for, and the place where decoded data goes:
/// the end of a GLB's binary chunk, or else a new buffer in a file of its own (`added_uri`).
class GltfBytes {
public:
  /// \p bin is the GLB's binary chunk (nullptr for .gltf or a GLB without one); \p dir the folder that
  /// relative URIs start from; \p shown_as the file's name in errors.
  GltfBytes(nlohmann::json& doc, std::string* bin, std::filesystem::path dir, std::string shown_as);

  /// The bytes of buffer view \p view (a copy: appending may move the buffers).
  std::string view_bytes(size_t view);
  /// \p length bytes of buffer \p buffer from \p offset; \p what names them in the error when they do not exist.
  std::string range(size_t buffer, size_t offset, size_t length, const std::string& what);
  /// Appends \p bytes as a new buffer view (4-byte aligned) and returns its index.
  size_t add_view(const std::string& bytes, size_t stride = 0);

  /// The decoded data that goes into a file of its own (empty when it all went into the GLB chunk).
  const std::string& added() const { return added_; }
  static constexpr const char* added_uri = "omsk-decoded.bin";

private:
  const std::string& buffer(size_t index);

  nlohmann::json& doc_;
  std::string* bin_;
  std::filesystem::path dir_;
  std::string shown_as_;
  std::vector<std::string> loaded_;
  std::vector<bool> is_loaded_;
  std::string added_;
  long target_ = -1;  // the buffer that decoded views point into (-1: not chosen yet)
};

/// Throws IOError naming the first extension in "extensionsRequired" that the tool cannot honour.
void check_required_extensions(const nlohmann::json& doc, const std::string& shown_as);

/// Decodes everything listed in the file's comment above; returns the names of what it decoded (empty:
/// \p doc is unchanged). Throws IOError, one line naming the file and the part, for data that cannot
/// be decoded (a meshopt vertex codec newer than Debian's library, corrupt streams).
std::vector<std::string> decompress_gltf(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as);

}  // namespace OpenMeshSkinned::detail
