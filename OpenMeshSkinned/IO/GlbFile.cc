#include "OpenMeshSkinned/IO/GlbFile.hh"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

namespace OpenMeshSkinned::detail {
namespace {

uint32_t le32(const std::string& s, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

}  // namespace

bool split_glb(const std::string& data, GlbChunks& out) {
  out = GlbChunks();
  if (data.size() < 20 || data.compare(0, 4, "glTF") != 0) return false;
  const uint32_t json_len = le32(data, 12);
  if (data.compare(16, 4, "JSON") != 0 || 20ull + json_len > data.size()) return false;
  out.json = data.substr(20, json_len);
  size_t at = 20 + json_len;
  if (at + 8 <= data.size() && data.compare(at + 4, 4, std::string("BIN\0", 4)) == 0 &&
      at + 8ull + le32(data, at) <= data.size()) {
    out.bin = data.substr(at + 8, le32(data, at));
    out.has_bin = true;
    at += 8 + le32(data, at);
  }
  out.rest = data.substr(std::min(at, data.size()));
  return true;
}

bool read_file_bytes(const std::filesystem::path& path, std::string& out) {
  out.clear();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  if (size < 0) {  // not seekable: read it as a stream
    in.clear();
    in.seekg(0);
    out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
  }
  out.resize(size_t(size));
  in.seekg(0);
  if (size > 0 && !in.read(out.data(), size)) {
    out.clear();
    return false;
  }
  return true;
}

std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace OpenMeshSkinned::detail
