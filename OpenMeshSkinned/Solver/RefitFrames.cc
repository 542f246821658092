#include "OpenMeshSkinned/Solver/RefitFrames.hh"

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <set>

namespace OpenMeshSkinned {

namespace {

// The pose of each stored frame: the rest shape (index 0) and every target alone at weight 1 (index t + 1),
// found among the poses at the clips' morph keys. Empty unless the clips play a frame animation: every key a
// blend of at most two shapes (weights >= 0 summing to at most 1), every target alone at some key. Between
// such keys a clip plays a blend of fitted shapes; any other mix (two targets added, a weight above 1) would
// add or extrapolate the frames' separate fits.
std::vector<Pose> frame_poses(const SkinnedMesh& mesh, size_t n_targets, bool& has_rest) {
  std::vector<Pose> out(n_targets + 1);
  std::vector<char> found(n_targets + 1, 0);
  for (const Clip& clip : clips(mesh)) {
    if (!clip.channels.empty()) return {};
    std::set<double> times;
    for (const MorphChannel& c : clip.morph_channels) times.insert(c.times.begin(), c.times.end());
    if (times.empty()) continue;
    for (const Pose& p : sample_poses_at(skeleton(mesh), clip, {times.begin(), times.end()})) {
      int alone = -1, nonzero = 0;
      double sum = 0.0;
      for (size_t t = 0; t < p.morph_weights.size(); ++t) {
        const double w = p.morph_weights[t];
        if (w < -1e-9 || (t >= n_targets && std::abs(w) > 1e-9)) return {};
        if (std::abs(w) <= 1e-9) continue;
        ++nonzero;
        sum += w;
        if (std::abs(w - 1.0) <= 1e-9) alone = int(t);
      }
      if (nonzero > 2 || sum > 1.0 + 1e-9) return {};
      if (nonzero > 1) continue;
      const size_t slot = nonzero == 0 ? 0 : alone >= 0 ? size_t(alone) + 1 : n_targets + 1;
      if (slot > n_targets || found[slot]) continue;
      found[slot] = 1;
      out[slot] = p;
      out[slot].morph_weights.assign(n_targets, 0.0);
      if (nonzero) out[slot].morph_weights[alone] = 1.0;
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
  std::vector<std::vector<Eigen::Vector3f>> moved(poses.size(),
                                                  std::vector<Eigen::Vector3f>(nv, Eigen::Vector3f::Zero()));
  std::atomic<size_t> next{has_rest ? 0u : 1u};
  std::exception_ptr failure;
  std::mutex failure_lock;
  run_on_threads(std::max(1, settings.threads), [&](int) {
    try {
      // One copy a thread, its points put back before each frame (the fit moves nothing else).
      SkinnedMesh work = lod;
      for (size_t f = next++; f < poses.size(); f = next++) {
        for (auto vh : work.vertices()) work.set_point(vh, lod.point(vh));
        refit_positions(work, original, {poses[f]}, one);
        for (auto vh : lod.vertices())
          moved[f][vh.idx()] = (to_eigen(work.point(vh)) - to_eigen(lod.point(vh))).cast<float>();
      }
    } catch (...) {
      std::lock_guard<std::mutex> g(failure_lock);
      if (!failure) failure = std::current_exception();
      next = poses.size();
    }
  });
  if (failure) std::rethrow_exception(failure);
  for (auto vh : lod.vertices()) {
    const int v = vh.idx();
    const Eigen::Vector3f rest_move = moved[0][v];
    lod.set_point(vh, lod.point(vh) + SkinnedMesh::Point(rest_move.x(), rest_move.y(), rest_move.z()));
    MorphDeltas& d = lod.property(hd, vh);
    d.resize(std::max(d.size(), n_targets), Eigen::Vector3f::Zero());
    for (size_t t = 0; t < n_targets; ++t) d[t] += moved[t + 1][v] - rest_move;
  }
  report.frames = poses.size() - (has_rest ? 0 : 1);
  return report;
}

}  // namespace OpenMeshSkinned
