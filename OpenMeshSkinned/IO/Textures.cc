#include "OpenMeshSkinned/IO/Textures.hh"

// Private copies of stb's decoder and PNG writer: tinygltf's shared library may carry its own.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_HDR
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace OpenMeshSkinned {
namespace {

bool starts_with(const std::vector<unsigned char>& b, std::initializer_list<unsigned char> magic) {
  return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* p = static_cast<const unsigned char*>(data);
  out->insert(out->end(), p, p + size);
}

}  // namespace

bool encode_rgba_png(const unsigned char* rgba, int width, int height, const std::string& name, Image& out) {
  out.name = name;
  out.mime_type = "image/png";
  out.data.clear();
  return stbi_write_png_to_func(append_bytes, &out.data, width, height, 4, rgba, width * 4) != 0 && !out.data.empty();
}

std::string image_stream_problem(const std::vector<unsigned char>& bytes) {
  if (starts_with(bytes, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) {
    for (size_t at = 8; at + 12 <= bytes.size();) {
      const size_t len =
          size_t(bytes[at]) << 24 | size_t(bytes[at + 1]) << 16 | size_t(bytes[at + 2]) << 8 | bytes[at + 3];
      if (len > bytes.size() - at - 12) break;
      if (std::equal(bytes.begin() + at + 4, bytes.begin() + at + 8, "IEND")) return {};
      at += 12 + len;
    }
    return "a PNG cut short (no IEND chunk where its chunks end)";
  }
  if (starts_with(bytes, {0xFF, 0xD8, 0xFF})) {
    // Entropy-coded data escapes 0xFF, so FF D9 stands only for the end-of-image marker.
    for (size_t at = bytes.size(); at >= 4; --at)
      if (bytes[at - 2] == 0xFF && bytes[at - 1] == 0xD9) return {};
    return "a JPEG cut short (no end-of-image marker)";
  }
  return {};
}

bool encode_for_gltf(const std::vector<unsigned char>& bytes, const std::string& name, Image& out,
                     std::string& problem) {
  if (starts_with(bytes, {0x89, 'P', 'N', 'G'}) || starts_with(bytes, {0xFF, 0xD8, 0xFF})) {
    problem = image_stream_problem(bytes);
    if (!problem.empty()) return false;
    out = {name, starts_with(bytes, {0x89, 'P', 'N', 'G'}) ? "image/png" : "image/jpeg", bytes};
    return true;
  }
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &n, 4);
  if (!px) {
    problem = std::string("not an image format that can be read (") + stbi_failure_reason() + ")";
    return false;
  }
  const bool ok = encode_rgba_png(px, w, h, name, out);
  stbi_image_free(px);
  if (!ok) problem = "could not be re-encoded as PNG";
  return ok;
}

std::string gltf_mime_type(const std::vector<unsigned char>& b) {
  if (starts_with(b, {0x89, 'P', 'N', 'G'})) return "image/png";
  if (starts_with(b, {0xFF, 0xD8, 0xFF})) return "image/jpeg";
  if (starts_with(b, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "image/ktx2";
  if (b.size() >= 12 && starts_with(b, {'R', 'I', 'F', 'F'}) && std::equal(b.begin() + 8, b.begin() + 12, "WEBP"))
    return "image/webp";
  return "";
}

bool decode_rgba(const Image& image, std::vector<unsigned char>& rgba, int& width, int& height) {
  int n = 0;
  unsigned char* px =
      stbi_load_from_memory(image.data.data(), static_cast<int>(image.data.size()), &width, &height, &n, 4);
  if (!px) return false;
  rgba.assign(px, px + size_t(width) * height * 4);
  stbi_image_free(px);
  return true;
}

bool find_texture_file(const std::string& stored, const std::string& source_dir, std::vector<unsigned char>& bytes,
                       std::string& name, std::string& problem) {
  namespace fs = std::filesystem;
  std::string norm = stored;
  std::replace(norm.begin(), norm.end(), '\\', '/');
  std::vector<fs::path> candidates;
  const fs::path as_stored(norm);
  candidates.push_back(as_stored.is_absolute() ? as_stored : fs::path(source_dir) / as_stored);
  // Windows paths ("C:/work/x.png") and paths from another machine: the file's name beside the source.
  name = norm.substr(norm.find_last_of('/') + 1);
  if (!name.empty() && fs::path(source_dir) / name != candidates.front())
    candidates.push_back(fs::path(source_dir) / name);
  for (const fs::path& p : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) continue;
    std::ifstream in(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (bytes.empty()) {
      problem = p.string() + " is empty";
      return false;
    }
    return true;
  }
  problem = "not found (looked for " + candidates.front().string() +
            (candidates.size() > 1 ? " and " + candidates.back().string() : std::string()) + ")";
  return false;
}

bool read_texture_file(const std::string& stored, const std::string& source_dir, Image& out, std::string& problem) {
  std::vector<unsigned char> bytes;
  std::string name;
  if (!find_texture_file(stored, source_dir, bytes, name, problem)) return false;
  if (!encode_for_gltf(bytes, name, out, problem)) {
    problem = name + ": " + problem;
    return false;
  }
  return true;
}

}  // namespace OpenMeshSkinned
