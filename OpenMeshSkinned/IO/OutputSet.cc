#include "OpenMeshSkinned/IO/OutputSet.hh"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace OpenMeshSkinned {
namespace {

namespace fs = std::filesystem;

// The same file: one name through symlinks and "..", or one inode (hard links).
bool same_file(const fs::path& a, const std::string& resolved_a, const fs::path& b) {
  std::error_code ec;
  if (fs::weakly_canonical(fs::absolute(b), ec).string() == resolved_a) return true;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

}  // namespace

OutputSet::OutputSet(std::vector<std::string> inputs) : inputs_(std::move(inputs)) {}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ec;
  for (const Entry& e : entries_) fs::remove(e.staged, ec);
}

std::string OutputSet::add(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  const std::string resolved = fs::weakly_canonical(fs::absolute(p), ec).string();
  for (const std::string& in : inputs_)
    if (same_file(p, resolved, in)) throw PathConflict(path + ": is the input " + in + "; refusing to overwrite it");
  for (const Entry& e : entries_)
    if (same_file(p, resolved, e.path))
      throw PathConflict(path + ": is also " + (e.path == path ? "named" : e.path) + " among this run's outputs");
  if (fs::is_directory(p, ec)) throw IOError(path + ": is a folder");

  const fs::path dir = fs::absolute(p).parent_path();
  if (!fs::is_directory(dir, ec)) throw IOError(path + ": folder " + dir.string() + " does not exist");
  const fs::path staged = dir / ("." + p.stem().string() + ".omsk-" + std::to_string(::getpid()) + "-" +
                                 std::to_string(entries_.size()) + p.extension().string());
  {
    std::ofstream probe(staged);
    if (!probe) throw IOError(path + ": folder " + dir.string() + " is not writable");
  }
  fs::remove(staged, ec);
  entries_.push_back({path, resolved, staged.string()});
  return entries_.back().staged;
}

const std::string& OutputSet::staging(const std::string& path) const {
  for (const Entry& e : entries_)
    if (e.path == path) return e.staged;
  throw std::logic_error("OutputSet: " + path + " was not planned");
}

void OutputSet::commit() {
  std::error_code ec;
  for (const Entry& e : entries_)
    if (!fs::exists(e.staged, ec)) throw IOError(e.path + ": was not written");
  // Renames within one folder are atomic each; keep what a failure part-way replaced, to put it back.
  std::vector<std::pair<std::string, std::string>> done;  // final, its previous content moved aside ("" if none)
  for (const Entry& e : entries_) {
    std::string backup;
    if (fs::exists(e.path, ec)) {
      backup = e.staged + ".old";  // a second name for it: the final name never disappears
      fs::create_hard_link(e.path, backup, ec);
      if (ec) backup.clear();
    }
    fs::rename(e.staged, e.path, ec);
    if (ec) {
      const std::string why = ec.message();
      if (!backup.empty()) fs::remove(backup, ec);
      for (auto it = done.rbegin(); it != done.rend(); ++it) {
        if (it->second.empty())
          fs::remove(it->first, ec);
        else
          fs::rename(it->second, it->first, ec);
      }
      throw IOError(e.path + ": cannot be written: " + why);
    }
    done.emplace_back(e.path, backup);
  }
  for (const auto& [path, backup] : done)
    if (!backup.empty()) fs::remove(backup, ec);
  committed_ = true;
}

}  // namespace OpenMeshSkinned
