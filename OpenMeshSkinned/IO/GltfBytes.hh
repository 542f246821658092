#pragma once
/** \file GltfBytes.hh
 *  A glTF document's buffers, read when first asked for, and the place its decoders (GltfDecompress.hh)
 *  put what they decode. Internal to the importer.
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

}  // namespace OpenMeshSkinned::detail
