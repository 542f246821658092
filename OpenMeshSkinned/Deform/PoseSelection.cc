#include "OpenMeshSkinned/Deform/PoseSelection.hh"

#include "OpenMeshSkinned/Skin/FrameAnimation.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace OpenMeshSkinned {

std::vector<PoseTime> candidate_frames(const SkinnedMesh& mesh, const std::vector<PoseTime>& held_out, int clip,
                                       double fps) {
  const auto& all = clips(mesh);
  std::vector<PoseTime> out;
  const std::vector<double>& stored = frame_times(mesh);
  const double step = stored.size() > 1 ? stored[1] - stored[0] : 1.0 / fps;
  auto unseen = [&](const PoseTime& t) {
    return std::none_of(held_out.begin(), held_out.end(),
                        [&](const PoseTime& h) { return h.clip == t.clip && std::abs(h.time - t.time) < 0.5 * step; });
  };
  if (!stored.empty()) {
    if (clip <= 0)
      for (double t : stored)
        if (unseen({0, t})) out.push_back({0, t});
    return out;
  }
  for (size_t c = 0; c < all.size(); ++c) {
    if (clip >= 0 && int(c) != clip) continue;
    // A clip without length is one frame, not two copies of it.
    const size_t n = all[c].duration > 0.0 ? std::max<size_t>(2, size_t(std::ceil(all[c].duration * fps)) + 1) : 1;
    for (size_t i = 0; i < n; ++i) {
      const PoseTime t{int(c), n == 1 ? 0.0 : all[c].duration * double(i) / double(n - 1)};
      if (unseen(t)) out.push_back(t);
    }
  }
  return out;
}

namespace {

// The mesh posed at \p t, every \p stride-th vertex only: selection needs the motion, not every vertex, and
// posing the whole of a large mesh at every candidate frame would cost more than the choice is worth.
FramePoints strided_posed(const SkinnedMesh& mesh, const Pose& pose, size_t stride) {
  const VertexPoser<SkinnedMesh> posed(mesh, pose);
  FramePoints out;
  for (size_t v = 0; v < mesh.n_vertices(); v += stride) out.push_back(posed(SkinnedMesh::VertexHandle(int(v))));
  return out;
}

size_t vertex_stride(const SkinnedMesh& mesh, size_t max_vertices) {
  return std::max<size_t>(1, (mesh.n_vertices() + max_vertices - 1) / std::max<size_t>(1, max_vertices));
}

// Every candidate posed at every \p stride-th vertex.
std::vector<FramePoints> posed_candidates(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates,
                                          size_t stride) {
  const auto& all = clips(mesh);
  std::vector<FramePoints> frames;
  for (const PoseTime& t : candidates)
    frames.push_back(strided_posed(mesh, sample_pose(skeleton(mesh), all.at(t.clip), t.time), stride));
  return frames;
}

std::vector<PoseTime> chosen_of(const std::vector<PoseTime>& candidates, const std::vector<char>& chosen) {
  std::vector<PoseTime> out;
  for (size_t f = 0; f < candidates.size(); ++f)
    if (chosen[f]) out.push_back(candidates[f]);
  return out;
}

double squared_distance(const FramePoints& a, const FramePoints& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]).squaredNorm();
  return d;
}

}  // namespace

std::vector<PoseTime> select_poses_spread(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                          bool from_bind_pose, size_t max_vertices) {
  if (candidates.empty()) throw std::invalid_argument("pose selection needs a candidate frame");
  k = std::min(std::max<size_t>(k, 1), candidates.size());
  const size_t stride = vertex_stride(mesh, max_vertices);
  const std::vector<FramePoints> frames = posed_candidates(mesh, candidates, stride);
  // The bind pose, when it is an example, is already one: the others are chosen farthest from it too. Without it,
  // the first candidate starts.
  std::vector<double> nearest(frames.size(), HUGE_VAL);
  if (from_bind_pose) {
    const FramePoints rest = strided_posed(mesh, Pose::identity(skeleton(mesh).size()), stride);
    for (size_t f = 0; f < frames.size(); ++f) nearest[f] = squared_distance(frames[f], rest);
  }
  std::vector<char> chosen(frames.size(), 0);
  for (size_t n = 0; n < k; ++n) {
    // The first unchosen frame unless one lies farther: a distance that is not a number never wins, and never
    // makes a frame be chosen twice.
    size_t best = frames.size();
    for (size_t f = 0; f < frames.size(); ++f)
      if (!chosen[f] && (best == frames.size() || nearest[f] > nearest[best])) best = f;
    chosen[best] = 1;
    for (size_t f = 0; f < frames.size(); ++f)
      nearest[f] = std::min(nearest[f], squared_distance(frames[f], frames[best]));
  }
  return chosen_of(candidates, chosen);
}

std::vector<PoseTime> select_poses_by_motion(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                             size_t max_vertices) {
  if (candidates.empty()) throw std::invalid_argument("pose selection needs a candidate frame");
  k = std::min(std::max<size_t>(k, 1), candidates.size());
  const std::vector<FramePoints> frames = posed_candidates(mesh, candidates, vertex_stride(mesh, max_vertices));
  // The motion so far at each candidate; a clip's first frame adds nothing (the jump from the clip before is not
  // motion).
  std::vector<double> s(candidates.size(), 0.0);
  for (size_t f = 1; f < candidates.size(); ++f) {
    const double step = std::sqrt(squared_distance(frames[f], frames[f - 1]));
    s[f] = s[f - 1] + (candidates[f].clip == candidates[f - 1].clip && std::isfinite(step) ? step : 0.0);
  }
  std::vector<char> chosen(candidates.size(), 0);
  for (size_t i = 0; i < k; ++i) {
    const double target = k == 1 ? 0.0 : s.back() * double(i) / double(k - 1);
    size_t best = candidates.size();
    for (size_t f = 0; f < candidates.size(); ++f)
      if (!chosen[f] && (best == candidates.size() || std::abs(s[f] - target) < std::abs(s[best] - target))) best = f;
    chosen[best] = 1;
  }
  return chosen_of(candidates, chosen);
}

std::vector<PoseTime> select_poses_ga(const SkinnedMesh& mesh, const std::vector<PoseTime>& candidates, size_t k,
                                      size_t max_vertices, const KeyframeGaSettings& settings) {
  if (candidates.size() < 2) throw std::invalid_argument("pose selection needs two or more candidate frames");
  k = std::min(std::max<size_t>(k, 2), candidates.size());
  const size_t stride = vertex_stride(mesh, max_vertices);
  const auto& all = clips(mesh);
  std::vector<double> start(all.size(), 0.0);
  for (size_t c = 1; c < all.size(); ++c) start[c] = start[c - 1] + all[c - 1].duration;
  const std::vector<FramePoints> frames = posed_candidates(mesh, candidates, stride);
  std::vector<double> times;
  for (const PoseTime& t : candidates) {
    // Laid end to end; a tiny gap keeps a clip's end and the next clip's start apart in time.
    times.push_back(start[t.clip] + t.time + 1e-6 * t.clip);
  }
  const InterpolationError err(frames, times);
  std::vector<PoseTime> out;
  for (size_t f : select_keyframes_ga(err, k, settings).frames) out.push_back(candidates[f]);
  return out;
}

}  // namespace OpenMeshSkinned
