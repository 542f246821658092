#include "OpenMeshSkinned/IO/ImportFrames.hh"

#include "OpenMeshSkinned/IO/Import.hh"

#include "OpenMeshSkinned/Skin/FrameAnimation.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>

namespace OpenMeshSkinned {

namespace {

namespace fs = std::filesystem;

}  // namespace

ImportReport import_frame_animation(const std::vector<std::string>& files, SkinnedMesh& mesh, const ImportOptions& opt,
                                    double fps) {
  if (files.empty()) throw IOError("no frame to read");
  if (!(fps > 0.0)) throw IOError("the frame rate must be positive");
  const bool stored = files.size() == 1;
  const size_t n = stored ? stored_frame_count(files[0]) : files.size();
  if (n < 2)
    throw IOError(files[0] + ": one frame only: not an animation (give a numbered sequence, or an MD2/MD3/MDL file)");
  ImportOptions o = opt;
  o.all_stored_frames = stored;
  if (!stored) o.frame_files.assign(files.begin() + 1, files.end());
  ImportReport rep = import_skinned(files[0], mesh, o);
  if (morph_targets(mesh).size() + 1 != n)
    throw IOError(files[0] + ": has morph targets of its own: a frame animation cannot be read from it");
  // A file whose stored frames all have frame 0's shape (or whose reader gives frame 0 for each) is a
  // still mesh: said, not dressed up as an animation.
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  bool moves = false;
  if (morph_deltas_handle(mesh, hd))
    for (auto vh : mesh.vertices())
      for (const auto& d : mesh.property(hd, vh)) moves |= d.squaredNorm() > 0.0f;
  if (!moves) {
    morph_targets(mesh).clear();
    if (morph_deltas_handle(mesh, hd)) mesh.remove_property(hd);
    rep.morph_targets = 0;
    rep.warnings.push_back(std::to_string(n) + " stored frames, all with the same shape (as the reader gives " +
                           "them): read as one still mesh");
    return rep;
  }
  std::vector<double> times;
  for (size_t f = 0; f < n; ++f) times.push_back(double(f) / fps);
  set_frame_times(mesh, times);
  rep.clips = 1;
  rep.morph_targets = n - 1;
  rep.warnings.push_back("read " + std::to_string(n) + " frames as one clip at " +
                         std::to_string(int(std::lround(fps))) +
                         " frames per second (frame 0 is the rest shape, each later frame a morph target)");
  return rep;
}

}  // namespace OpenMeshSkinned
