#include "OpenMeshSkinned/IO/GltfRepair.hh"

#include "OpenMeshSkinned/IO/GlbFile.hh"
#include "OpenMeshSkinned/IO/GltfDecompress.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <cereal/external/base64.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace OpenMeshSkinned {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

void put32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

// Adds identity inverse bind matrices to every skin without them; false when none was missing.
bool add_identity_inverse_binds(json& doc) {
  if (!doc.contains("skins") || !doc["skins"].is_array()) return false;
  bool changed = false;
  for (auto& skin : doc["skins"]) {
    if (!skin.is_object() || skin.contains("inverseBindMatrices") || !skin.contains("joints") ||
        !skin["joints"].is_array() || skin["joints"].empty())
      continue;
    const size_t n = skin["joints"].size();
    std::vector<float> m(16 * n, 0.0f);
    for (size_t j = 0; j < n; ++j)
      for (int d = 0; d < 4; ++d) m[16 * j + 5 * d] = 1.0f;
    const auto* bytes = reinterpret_cast<const unsigned char*>(m.data());
    const size_t length = m.size() * sizeof(float);
    auto& buffers = doc["buffers"];
    auto& views = doc["bufferViews"];
    auto& accessors = doc["accessors"];
    buffers.push_back({{"byteLength", length},
                       {"uri", "data:application/octet-stream;base64," + cereal::base64::encode(bytes, length)}});
    views.push_back({{"buffer", buffers.size() - 1}, {"byteLength", length}});
    accessors.push_back({{"bufferView", views.size() - 1}, {"componentType", 5126}, {"count", n}, {"type", "MAT4"}});
    skin["inverseBindMatrices"] = accessors.size() - 1;
    changed = true;
  }
  return changed;
}

// A .gltf's external buffers and images, linked into the scratch folder so that the copy finds them.
void link_resources(const json& doc, const fs::path& source_dir, const fs::path& scratch, const std::string& path,
                    const std::string& why) {
  for (const char* kind : {"buffers", "images"}) {
    if (!doc.contains(kind) || !doc[kind].is_array()) continue;
    for (const auto& r : doc[kind]) {
      if (!r.is_object() || !r.contains("uri") || !r["uri"].is_string()) continue;
      const std::string uri = r["uri"];
      if (uri.rfind("data:", 0) == 0 || uri == detail::GltfBytes::added_uri) continue;
      const fs::path rel(uri);
      bool outside = rel.is_absolute() || uri.find(':') != std::string::npos;
      for (const auto& part : rel) outside |= part == "..";
      // The materials' images are read from beside the file the user named (GltfMaterials.hh), not through
      // the copy: one elsewhere (an absolute Windows path) needs no link.
      if (outside && std::string(kind) == "images") continue;
      if (outside)
        throw IOError(path + ": has " + why + " (which assimp 5.2 cannot read) and refers to \"" + uri +
                      "\" outside its folder, so it cannot be rewritten on the way in");
      const fs::path target = fs::absolute(source_dir / rel);
      if (!fs::exists(target)) continue;  // the reader reports the missing file
      fs::create_directories((scratch / rel).parent_path());
      fs::create_symlink(target, scratch / rel);
    }
  }
}

// A GLB of \p json_text, the binary chunk \p bin (padded here) and the chunks after it as they were.
std::string glb_file(std::string json_text, std::string& bin, const std::string& other_chunks) {
  while (json_text.size() % 4) json_text += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string file = "glTF";
  put32(file, 2);
  put32(file, uint32_t(12 + 8 + json_text.size() + 8 + bin.size() + other_chunks.size()));
  put32(file, uint32_t(json_text.size()));
  file += "JSON";
  file += json_text;
  put32(file, uint32_t(bin.size()));
  file.append("BIN\0", 4);
  file += bin;
  return file + other_chunks;
}

// Every repair \p doc needs, made on it; what each was for (empty: none was needed). \p glb_without_chunk:
// the file is a GLB with no binary chunk. Adds to \p notes what the user should know.
std::vector<std::string> repairs(json& doc, detail::GltfBytes& bytes, const std::string& path, bool glb_without_chunk,
                                 std::vector<std::string>& notes) {
  std::vector<std::string> why;
  try {
    detail::check_required_extensions(doc, path);
    why = detail::decompress_gltf(doc, bytes, path, notes);
    if (add_identity_inverse_binds(doc)) why.push_back("a skin without inverseBindMatrices");
    // assimp 5.2 takes a GLB's first buffer for its binary chunk even when it has none and the buffer is a
    // URI; the copy is written as .gltf instead, which reads every buffer from its URI.
    if (glb_without_chunk && doc.contains("buffers") && doc["buffers"].is_array() && !doc["buffers"].empty())
      why.push_back("a GLB without a binary chunk");
  } catch (const json::exception& e) {
    // A field of the wrong type (a string where a count belongs): the file's fault, said as such.
    throw IOError(path + ": a glTF field has the wrong type (" + e.what() + ")");
  } catch (const std::logic_error& e) {  // std::stoul and friends on a malformed attribute name
    throw IOError(path + ": a glTF field is malformed (" + e.what() + ")");
  }
  return why;
}

}  // namespace

RepairedGltf::RepairedGltf(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  const bool glb = ext == ".glb" || ext == ".GLB";
  if (!glb && ext != ".gltf" && ext != ".GLTF") return;
  std::string data;
  detail::read_file_bytes(path, data);  // unreadable: empty, and the reader says why

  json doc;
  detail::GlbChunks chunks;
  if (glb) {
    if (!detail::split_glb(data, chunks)) return;
    doc = json::parse(chunks.json, nullptr, false);
  } else {
    doc = json::parse(data, nullptr, false);
  }
  std::string& bin = chunks.bin;  // the GLB's binary chunk (its payload)
  const bool has_bin = chunks.has_bin;
  const std::string& other_chunks = chunks.rest;       // every chunk after those two, as it is
  if (doc.is_discarded() || !doc.is_object()) return;  // the reader judges
  const fs::path source_dir = fs::absolute(fs::path(path)).parent_path();
  detail::GltfBytes bytes(doc, has_bin ? &bin : nullptr, source_dir, path);
  const std::vector<std::string> why = repairs(doc, bytes, path, glb && !has_bin, notes_);
  if (why.empty()) return;
  std::string reasons;
  for (const std::string& w : why) reasons += (reasons.empty() ? "" : ", ") + w;

  std::string tmpl = (fs::temp_directory_path() / "omsk-gltf-XXXXXX").string();
  if (!::mkdtemp(tmpl.data()))
    throw IOError(path + ": no temporary folder for a repaired copy: " + std::strerror(errno));
  dir_ = tmpl;
  try {
    const fs::path scratch(dir_);
    const bool as_glb = glb && (has_bin || !bin.empty());
    const fs::path out =
        scratch / (as_glb || !glb ? fs::path(path).filename() : fs::path(path).filename().replace_extension(".gltf"));
    const std::string file = as_glb ? glb_file(doc.dump(), bin, other_chunks) : doc.dump();
    link_resources(doc, source_dir, scratch, path, reasons);
    if (!bytes.added().empty()) {
      std::ofstream b(scratch / detail::GltfBytes::added_uri, std::ios::binary);
      b << bytes.added();
      if (!b) throw IOError(path + ": the decoded data cannot be written to " + dir_);
    }
    std::ofstream f(out, std::ios::binary);
    f << file;
    if (!f) throw IOError(path + ": the repaired copy cannot be written to " + dir_);
    path_ = out.string();
  } catch (...) {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    throw;
  }
}

RepairedGltf::~RepairedGltf() {
  std::error_code ec;
  if (!dir_.empty()) fs::remove_all(dir_, ec);
}

}  // namespace OpenMeshSkinned
