#include "OpenMeshSkinned/IO/GltfResources.hh"

#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/Textures.hh"

#include <cereal/external/base64.hpp>

#include <cctype>
#include <filesystem>

namespace OpenMeshSkinned {

namespace fs = std::filesystem;
using json = nlohmann::json;

bool load_gltf_document(const std::string& path, json& doc, std::vector<unsigned char>& bin) {
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

namespace {

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

}  // namespace

GltfResources::GltfResources(const json& doc, std::vector<unsigned char> bin, std::string source_dir)
    : doc_(doc), bin_(std::move(bin)), dir_(std::move(source_dir)) {}

bool GltfResources::image(int i, std::shared_ptr<const Image>& out, std::string& problem) {
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

const nlohmann::json* GltfResources::at(const char* kind, int i) const {
  if (!doc_.contains(kind) || !doc_[kind].is_array() || i < 0 || size_t(i) >= doc_[kind].size()) return nullptr;
  return doc_[kind][size_t(i)].is_object() ? &doc_[kind][size_t(i)] : nullptr;
}

bool GltfResources::buffer(int b, const std::vector<unsigned char>*& out, std::string& problem) {
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

bool GltfResources::read_image(int i, Image& out, std::string& problem) {
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

}  // namespace OpenMeshSkinned
