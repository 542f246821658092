#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <cereal/external/base64.hpp>

namespace OpenMeshSkinned::detail {

namespace fs = std::filesystem;
using json = nlohmann::json;

GltfBytes::GltfBytes(json& doc, std::string* bin, fs::path dir, std::string shown_as)
    : doc_(doc), bin_(bin), dir_(std::move(dir)), shown_as_(std::move(shown_as)) {}

const std::string& GltfBytes::buffer(size_t index) {
  json& buffers = array_of(doc_, "buffers");
  if (index >= buffers.size()) throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " does not exist");
  if (long(index) == target_ && !bin_) return added_;
  const json& b = buffers[index];
  if (!b.contains("uri")) {
    if (index == 0 && bin_) return *bin_;
    throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " has no data (no \"uri\" and no binary chunk)");
  }
  if (loaded_.size() <= index) loaded_.resize(buffers.size()), is_loaded_.resize(buffers.size(), false);
  if (is_loaded_[index]) return loaded_[index];
  const std::string uri = b["uri"].is_string() ? b["uri"].get<std::string>() : "";
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
      throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " has a data URI that is not base64");
    loaded_[index] = cereal::base64::decode(uri.substr(comma + 1));
  } else {
    if (!read_file_bytes(dir_ / percent_decoded(uri), loaded_[index]))
      throw IOError(shown_as_ + ": buffer " + std::to_string(index) + " (\"" + uri + "\") cannot be read");
  }
  is_loaded_[index] = true;
  return loaded_[index];
}

std::string GltfBytes::range(size_t buffer_index, size_t offset, size_t length, const std::string& what) {
  const std::string& data = buffer(buffer_index);
  if (offset > data.size() || length > data.size() - offset) throw IOError(what + " runs past its buffer");
  return data.substr(offset, length);
}

std::string GltfBytes::view_bytes(size_t index) {
  json& views = array_of(doc_, "bufferViews");
  const std::string what = shown_as_ + ": buffer view " + std::to_string(index);
  if (index >= views.size()) throw IOError(what + " does not exist");
  const json& v = views[index];
  return range(index_in(v, "buffer", array_of(doc_, "buffers").size(), what), v.value("byteOffset", size_t(0)),
               v.value("byteLength", size_t(0)), what);
}

size_t GltfBytes::add_view(const std::string& bytes, size_t stride) {
  json& buffers = array_of(doc_, "buffers");
  if (target_ < 0) {
    if (bin_ && !buffers.empty() && !buffers[0].contains("uri")) {
      target_ = 0;
    } else {
      bin_ = nullptr;  // a GLB whose chunk is not buffer 0 gets a file too
      target_ = long(buffers.size());
      buffers.push_back({{"byteLength", 0}, {"uri", added_uri}});
    }
  }
  std::string& out = bin_ ? *bin_ : added_;
  while (out.size() % 4) out += '\0';
  const size_t offset = out.size();
  out += bytes;
  buffers[size_t(target_)]["byteLength"] = out.size();
  json view = {{"buffer", size_t(target_)}, {"byteOffset", offset}, {"byteLength", bytes.size()}};
  if (stride) view["byteStride"] = stride;
  array_of(doc_, "bufferViews").push_back(view);
  return doc_["bufferViews"].size() - 1;
}

}  // namespace OpenMeshSkinned::detail
