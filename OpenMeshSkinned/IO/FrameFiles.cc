#include "FrameFiles.hh"

#include "ImportFrames.hh"

#include <cctype>
#include <filesystem>

namespace OpenMeshSkinned {

std::vector<std::string> frame_files(const std::string& input, bool sequences) {
  if (stored_frame_count(input) > 1) return {input};
  // Only formats that hold one still mesh make sequences: a "hero_2.glb" beside "hero_1.glb" is two
  // versions of a character, not two frames.
  std::string ext = std::filesystem::path(input).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (!sequences || (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")) return {};
  std::vector<std::string> seq = numbered_sequence(input);
  return seq.size() >= 2 ? seq : std::vector<std::string>{};
}

double frame_rate(const std::vector<std::string>& files, double fps) {
  if (fps > 0.0) return fps;
  return files.size() == 1 ? 10.0 : 24.0;
}

}  // namespace OpenMeshSkinned
