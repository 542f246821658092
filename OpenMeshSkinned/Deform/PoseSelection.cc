#include "OpenMeshSkinned/Deform/PoseSelection.hh"

#include "OpenMeshSkinned/Skin/FrameAnimation.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace OpenMeshSkinned {

std::vector<PoseTime> candidate_frames(const SkinnedMesh& mesh, const std::vector<PoseTime>& held_out, double fps) {
  const auto& all = clips(mesh);
  std::vector<PoseTime> out;
  const std::vector<double>& stored = frame_times(mesh);
  const double step = stored.size() > 1 ? stored[1] - stored[0] : 1.0 / fps;
  auto unseen = [&](const PoseTime& t) {
    return std::none_of(held_out.begin(), held_out.end(),
                        [&](const PoseTime& h) { return h.clip == t.clip && std::abs(h.time - t.time) < 0.5 * step; });
  };
  if (!stored.empty()) {
    for (double t : stored)
      if (unseen({0, t})) out.push_back({0, t});
    return out;
  }
  for (size_t c = 0; c < all.size(); ++c) {
    const size_t n = std::max<size_t>(2, size_t(std::ceil(all[c].duration * fps)) + 1);
    for (size_t i = 0; i < n; ++i) {
      const PoseTime t{int(c), all[c].duration * double(i) / double(n - 1)};
      if (unseen(t)) out.push_back(t);
    }
  }
  return out;
}

std::vector<PoseTime> select_poses_ga(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                      size_t max_vertices, const KeyframeGaSettings& settings) {
  if (candidates.size() < 2) throw std::invalid_argument("pose selection needs two or more candidate frames");
  k = std::min(std::max<size_t>(k, 2), candidates.size());
  const size_t stride = std::max<size_t>(1, (mesh.n_vertices() + max_vertices - 1) / std::max<size_t>(1, max_vertices));
  const auto& all = clips(mesh);
  std::vector<double> start(all.size(), 0.0);
  for (size_t c = 1; c < all.size(); ++c) start[c] = start[c - 1] + all[c - 1].duration;
  std::vector<FramePoints> frames;
  std::vector<double> times;
  for (const PoseTime& t : candidates) {
    const auto posed = skin_positions(mesh, sample_pose(skeleton(mesh), all.at(t.clip), t.time));
    FramePoints p;
    for (size_t v = 0; v < posed.size(); v += stride) p.push_back(posed[v]);
    frames.push_back(std::move(p));
    // Laid end to end; a tiny gap keeps a clip's end and the next clip's start apart in time.
    times.push_back(start[t.clip] + t.time + 1e-6 * t.clip);
  }
  const InterpolationError err(frames, times);
  std::vector<PoseTime> out;
  for (size_t f : select_keyframes_ga(err, k, settings).frames) out.push_back(candidates[f]);
  return out;
}

}  // namespace OpenMeshSkinned
