// The assets of a batch and the names their outputs take.
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/ImportFrames.hh"
#include "OpenMeshSkinned/Lod/Batch.hh"

#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

namespace OpenMeshSkinned {

namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool hidden(const fs::path& p) {
  const std::string n = p.filename().string();
  return !n.empty() && n[0] == '.';
}

// The tool reads what assimp reads; an .md5anim or .md5camera only adds motion to the .md5mesh beside it,
// and of XML only Ogre's .mesh.xml is a mesh (assimp lists ".xml" for it).
bool readable(const fs::path& p, const Assimp::Importer& importer) {
  const std::string name = lower(p.filename().string());
  const std::string ext = lower(p.extension().string());
  if (ext.empty() || ext == ".md5anim" || ext == ".md5camera") return false;
  if (ext == ".xml") return name.size() > 9 && name.compare(name.size() - 9, 9, ".mesh.xml") == 0;
  return importer.IsExtensionSupported(ext);
}

bool sequence_format(const fs::path& p) {
  const std::string ext = lower(p.extension().string());
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off";
}

// "chars/hero.fbx" -> "chars/hero" ("chars/hero.mesh.xml" -> "chars/hero").
std::string without_extension(const std::string& rel) {
  fs::path p(rel);
  const std::string name = lower(p.filename().string());
  const size_t cut = name.size() > 9 && name.compare(name.size() - 9, 9, ".mesh.xml") == 0
                         ? p.filename().string().size() - 9
                         : p.stem().string().size();
  return (p.parent_path() / p.filename().string().substr(0, cut)).generic_string();
}

// Names from paths below a common folder: without the extension, unless that clashes with another
// input, with another's LOD files (NAME_lod2.glb with --lods), or with the summary page (index.html).
std::vector<BatchInput> name_inputs(const std::vector<std::pair<std::string, std::string>>& path_and_rel) {
  std::map<std::string, int> count;
  std::vector<std::string> names;
  for (const auto& [path, rel] : path_and_rel) {
    names.push_back(without_extension(rel));
    ++count[names.back()];
  }
  const std::regex lod_name("(.*)_lod[0-9]+");
  std::vector<BatchInput> out;
  std::set<std::string> taken;
  for (size_t i = 0; i < names.size(); ++i) {
    std::smatch m;
    const bool lod_clash = std::regex_match(names[i], m, lod_name) && count.count(m[1].str()) > 0;
    const bool keep_extension = count[names[i]] > 1 || lod_clash || names[i] == "index";
    const std::string name = keep_extension ? fs::path(path_and_rel[i].second).generic_string() : names[i];
    if (!taken.insert(name).second)
      throw IOError(path_and_rel[i].first + ": its outputs would take the name " + name +
                    " of another input's; rename one of them");
    out.push_back({path_and_rel[i].first, name});
  }
  return out;
}

}  // namespace

std::vector<BatchInput> find_inputs(const std::string& dir, const std::string& out_dir, bool sequences) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw IOError(dir + ": is not a folder");
  const Assimp::Importer importer;
  std::vector<std::pair<std::string, std::string>> found;
  std::set<std::string> in_sequence;  // frames after the first of a numbered sequence
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
  if (ec) throw IOError(dir + ": cannot be read: " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw IOError(dir + ": cannot be read: " + ec.message());
    const fs::path p = it->path();
    if (hidden(p)) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (it->is_directory(ec)) {
      if (!out_dir.empty() && fs::equivalent(p, out_dir, ec)) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec) || !readable(p, importer)) continue;
    found.emplace_back(p.string(), p.lexically_relative(dir).generic_string());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  if (sequences) {
    std::vector<std::pair<std::string, std::string>> kept;
    for (const auto& f : found) {
      if (in_sequence.count(f.first)) continue;
      if (sequence_format(f.first)) {
        const std::vector<std::string> seq = numbered_sequence(f.first);
        if (seq.size() >= 2) {
          for (size_t i = 1; i < seq.size(); ++i) in_sequence.insert(fs::path(seq[i]).string());
          if (fs::path(seq.front()).string() != f.first) continue;
        }
      }
      kept.push_back(f);
    }
    found = std::move(kept);
  }
  return name_inputs(found);
}

std::vector<BatchInput> batch_inputs(const std::vector<std::string>& paths) {
  // The folder every path is in: their longest common parent.
  std::vector<fs::path> abs;
  for (const std::string& p : paths) abs.push_back(fs::absolute(p).lexically_normal());
  fs::path root = abs.empty() ? fs::path() : abs.front().parent_path();
  for (const fs::path& p : abs) {
    fs::path common;
    auto a = root.begin(), b = p.begin();
    for (; a != root.end() && b != p.end() && *a == *b; ++a, ++b) common /= *a;
    root = common;
  }
  std::vector<std::pair<std::string, std::string>> named;
  for (size_t i = 0; i < paths.size(); ++i)
    named.emplace_back(paths[i], abs[i].lexically_relative(root).generic_string());
  return name_inputs(named);
}

}  // namespace OpenMeshSkinned
