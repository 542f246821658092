#include "OpenMeshSkinned/IO/StoredFrames.hh"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>

namespace OpenMeshSkinned {

namespace {

namespace fs = std::filesystem;

// The little-endian int32 at \p offset of \p header (0 when the header is shorter).
int32_t le_i32(const std::vector<unsigned char>& header, size_t offset) {
  if (header.size() < offset + 4) return 0;
  const unsigned char* b = header.data() + offset;
  return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
}

}  // namespace

size_t stored_frame_count(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::vector<unsigned char> header(80, 0);
  f.read(reinterpret_cast<char*>(header.data()), std::streamsize(header.size()));
  header.resize(size_t(f.gcount()));
  if (header.size() < 4) return 1;
  auto ident = [&](const char* id, size_t n) { return std::memcmp(header.data(), id, n) == 0; };
  // Header layouts: id Software's md2.h / md3.h / modelgen.h (little-endian int32 fields); 3D GameStudio's
  // MDL2-MDL5 share Quake's MDL header (MDL7 does not, and stores no frames assimp reads).
  int32_t n = 1;
  if (ident("IDP2", 4))
    n = le_i32(header, 40);  // MD2: num_frames
  else if (ident("IDP3", 4))
    n = le_i32(header, 76);  // MD3: after name[64] and flags
  else if (ident("IDPO", 4) || (ident("MDL", 3) && header[3] >= '2' && header[3] <= '5'))
    n = le_i32(header, 68);  // MDL: after the scale, origin, radius, eye, skin and counts
  return n > 0 ? size_t(n) : 1;
}

std::vector<std::string> numbered_sequence(const std::string& path) {
  const fs::path p(path);
  static const std::regex numbered(R"((.*?)(\d+))");
  std::smatch m;
  const std::string stem = p.stem().string();
  if (!std::regex_match(stem, m, numbered)) return {path};
  const std::string prefix = m[1].str(), ext = p.extension().string();
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::vector<std::pair<unsigned long long, std::string>> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string s = e.path().stem().string();
    if (e.path().extension().string() != ext || s.size() <= prefix.size() || s.compare(0, prefix.size(), prefix) != 0)
      continue;
    const std::string digits = s.substr(prefix.size());
    if (digits.size() > 18 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    found.emplace_back(std::stoull(digits), (p.parent_path() / e.path().filename()).string());
  }
  if (found.empty()) return {path};
  std::sort(found.begin(), found.end());
  std::vector<std::string> out;
  for (auto& [n, s] : found) out.push_back(s);
  return out;
}

}  // namespace OpenMeshSkinned
