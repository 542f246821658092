#include "LodOptions.hh"

#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/Influences.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {

namespace {

// Largest first, the two lists in step.
void sort_lod_targets(std::vector<double>& ratios, std::vector<size_t>& targets) {
  std::vector<size_t> order(targets.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return targets[a] > targets[b]; });
  std::vector<double> r;
  std::vector<size_t> t;
  for (size_t i : order) r.push_back(ratios[i]), t.push_back(targets[i]);
  ratios = r;
  targets = t;
}

}  // namespace

bool morph_animated_only(const SkinnedMesh& mesh) {
  const auto& all = clips(mesh);
  return std::any_of(all.begin(), all.end(), [](const Clip& c) { return !c.morph_channels.empty(); }) &&
         std::all_of(all.begin(), all.end(), [](const Clip& c) { return c.channels.empty(); });
}

std::string lod_method_for(const LodOptions& o, const SkinnedMesh& mesh) {
  if (!o.method.empty()) return o.method;
  // Only the frame quadric sees morph-target frames; the skinned solver's methods decimate them in the rest
  // shape (their morph offsets carried along).
  return morph_animated_only(mesh) ? "frames" : "skinned";
}

int lod_pose_clip(const LodOptions& o, const SkinnedMesh& mesh, const std::string& name) {
  const auto& all = clips(mesh);
  const std::string& which = o.pose_clip;
  if (which.empty() || all.empty()) return -1;
  for (size_t c = 0; c < all.size(); ++c)
    if (all[c].name == which) return int(c);
  if (std::all_of(which.begin(), which.end(), ::isdigit) && which.size() < 9 && std::stoi(which) < int(all.size()))
    return std::stoi(which);
  throw LodOptionsError("--pose-clip " + which + ": no such clip in " + name + " (" + std::to_string(all.size()) +
                        " clips)");
}

void lod_targets(const LodOptions& o, const SkinnedMesh& mesh, std::vector<double>& ratios,
                 std::vector<size_t>& targets) {
  ratios.clear();
  targets.clear();
  if (!o.faces.empty()) {
    targets = o.faces;
    for (size_t f : o.faces) ratios.push_back(double(f) / mesh.n_faces());
  } else {
    ratios = o.ratios;
    for (double r : ratios)
      targets.push_back(std::max<size_t>(1, static_cast<size_t>(std::llround(r * mesh.n_faces()))));
  }
  // One pass of the decimater passes the targets in order.
  sort_lod_targets(ratios, targets);
}

}  // namespace OpenMeshSkinned
