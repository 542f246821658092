#include "OpenMeshSkinned/Solver/RefitFrames.hh"

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <set>

namespace OpenMeshSkinned {

namespace {

// The pose of each stored frame: the rest shape (index 0) and every target alone at weight 1 (index t + 1),
// found among the poses at the clips' morph keys. Empty when some target is never played alone.
std::vector<Pose> frame_poses(const SkinnedMesh& mesh, size_t n_targets, bool& has_rest) {
  std::vector<Pose> out(n_targets + 1);
  std::vector<char> found(n_targets + 1, 0);
  for (const Clip& clip : clips(mesh)) {
    std::set<double> times;
    for (const MorphChannel& c : clip.morph_channels) times.insert(c.times.begin(), c.times.end());
    if (times.empty()) continue;
    const std::vector<Pose> poses = sample_poses_at(skeleton(mesh), clip, {times.begin(), times.end()});
    for (const Pose& p : poses) {
      int alone = -1, on = 0;
      bool clean = true;
      for (size_t t = 0; t < p.morph_weights.size() && clean; ++t) {
        const double w = p.morph_weights[t];
        if (std::abs(w) <= 1e-9) continue;
        if (std::abs(w - 1.0) <= 1e-9 && t < n_targets) {
          alone = int(t);
          ++on;
        } else {
          clean = false;
        }
      }
      if (!clean || on > 1) continue;
      const size_t slot = on == 0 ? 0 : size_t(alone) + 1;
      if (found[slot]) continue;
      found[slot] = 1;
      out[slot] = p;
      out[slot].morph_weights.assign(n_targets, 0.0);
      if (on) out[slot].morph_weights[alone] = 1.0;
    }
  }
  has_rest = found[0];
  for (size_t t = 1; t <= n_targets; ++t)
    if (!found[t]) return {};
  return out;
}

}  // namespace

RefitFramesReport refit_frames(SkinnedMesh& lod, const SkinnedMesh& original, const RefitSettings& settings) {
  RefitFramesReport report;
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  const size_t n_targets = morph_targets(lod).size();
  if (n_targets == 0 || !morph_deltas_handle(lod, hd) || lod.n_faces() == 0) return report;
  bool has_rest = false;
  const std::vector<Pose> poses = frame_poses(lod, n_targets, has_rest);
  if (poses.empty()) return report;
  RefitSettings one = settings;
  one.fit_weights = false;
  one.threads = 1;
  const size_t nv = lod.n_vertices();
  // moved[f][v]: how far frame f's fit moved vertex v (rest space).
  std::vector<std::vector<Eigen::Vector3d>> moved(poses.size(),
                                                  std::vector<Eigen::Vector3d>(nv, Eigen::Vector3d::Zero()));
  std::atomic<size_t> next{has_rest ? 0u : 1u};
  run_on_threads(std::max(1, settings.threads), [&](int) {
    for (size_t f = next++; f < poses.size(); f = next++) {
      SkinnedMesh work = lod;
      refit_positions(work, original, {poses[f]}, one);
      for (auto vh : lod.vertices()) moved[f][vh.idx()] = to_eigen(work.point(vh)) - to_eigen(lod.point(vh));
    }
  });
  for (auto vh : lod.vertices()) {
    const int v = vh.idx();
    const Eigen::Vector3d rest_move = moved[0][v];
    lod.set_point(vh, lod.point(vh) + SkinnedMesh::Point(rest_move.x(), rest_move.y(), rest_move.z()));
    MorphDeltas& d = lod.property(hd, vh);
    for (size_t t = 0; t < n_targets && t < d.size(); ++t) d[t] += (moved[t + 1][v] - rest_move).cast<float>();
  }
  report.frames = poses.size() - (has_rest ? 0 : 1);
  return report;
}

}  // namespace OpenMeshSkinned
