#include "OpenMeshSkinned/Skin/PoseSchedule.hh"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace OpenMeshSkinned {
namespace {

// Position s on the clips laid end to end -> (clip, local time). A boundary belongs to the next clip,
// except the very end, which is the last clip's last frame.
PoseTime locate(const std::vector<Clip>& clips, double s) {
  for (size_t c = 0; c < clips.size(); ++c) {
    if (s < clips[c].duration || c + 1 == clips.size()) return {int(c), std::min(s, clips[c].duration)};
    s -= clips[c].duration;
  }
  return {0, 0.0};
}

std::vector<PoseTime> thin(const std::vector<PoseTime>& v, size_t n) {
  if (v.size() <= n) return v;
  std::vector<PoseTime> out;
  for (size_t i = 0; i < n; ++i) out.push_back(v[i * v.size() / n]);
  return out;
}

}  // namespace

PoseSchedule make_pose_schedule(const std::vector<Clip>& clips, int k, int clip_index, size_t max_held_out) {
  if (k < 1) throw std::invalid_argument("the number of example poses must be at least 1");
  if (clips.empty()) throw std::invalid_argument("there is no animation clip to take poses from");
  if (clip_index >= static_cast<int>(clips.size()))
    throw std::invalid_argument("clip index " + std::to_string(clip_index) + " out of range (" +
                                std::to_string(clips.size()) + " clips)");
  PoseSchedule s;
  if (clip_index >= 0) {
    const double d = clips[clip_index].duration;
    for (int i = 0; i < k; ++i) s.examples.push_back({clip_index, k == 1 ? 0.0 : d * i / (k - 1)});
    if (k == 1) {
      if (d > 0.0) s.held_out.push_back({clip_index, 0.5 * d});
    } else {
      for (int i = 0; i + 1 < k; ++i) s.held_out.push_back({clip_index, d * (i + 0.5) / (k - 1)});
    }
    for (size_t c = 0; c < clips.size(); ++c)
      if (static_cast<int>(c) != clip_index)
        for (double f : {0.125, 0.375, 0.625, 0.875}) s.held_out.push_back({int(c), f * clips[c].duration});
  } else {
    double total = 0.0;
    for (const Clip& c : clips) total += c.duration;
    for (int i = 0; i < k; ++i) s.examples.push_back(locate(clips, k == 1 ? 0.0 : total * i / (k - 1)));
    if (k == 1) {
      if (total > 0.0) s.held_out.push_back(locate(clips, 0.5 * total));
    } else {
      for (int i = 0; i + 1 < k; ++i) s.held_out.push_back(locate(clips, total * (i + 0.5) / (k - 1)));
    }
  }
  s.held_out = thin(s.held_out, max_held_out);
  return s;
}

void snap_to_frames(PoseSchedule& s, const std::vector<double>& frame_times) {
  if (frame_times.empty()) return;
  auto nearest = [&](double t, const std::vector<char>& taken) {
    long best = -1;
    for (size_t f = 0; f < frame_times.size(); ++f)
      if (!taken[f] && (best < 0 || std::abs(frame_times[f] - t) < std::abs(frame_times[size_t(best)] - t)))
        best = long(f);
    return best;
  };
  std::vector<char> none(frame_times.size(), 0), example(frame_times.size(), 0), held(frame_times.size(), 0);
  std::vector<PoseTime> examples, held_out;
  for (const PoseTime& t : s.examples) {
    const long f = nearest(t.time, none);
    if (!example[size_t(f)]) examples.push_back({t.clip, frame_times[size_t(f)]});
    example[size_t(f)] = 1;
  }
  for (const PoseTime& t : s.held_out) {
    const long f = nearest(t.time, example);
    if (f < 0 || held[size_t(f)]) continue;
    held[size_t(f)] = 1;
    held_out.push_back({t.clip, frame_times[size_t(f)]});
  }
  s.examples = std::move(examples);
  s.held_out = std::move(held_out);
}

std::vector<Pose> poses_at(const Skeleton& skel, const std::vector<Clip>& clips, const std::vector<PoseTime>& times) {
  std::vector<Pose> out;
  for (const PoseTime& t : times) out.push_back(sample_pose(skel, clips.at(t.clip), t.time));
  return out;
}

}  // namespace OpenMeshSkinned
