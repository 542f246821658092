#include "OpenMeshSkinned/Skin/FrameAnimation.hh"

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <cstdio>
#include <stdexcept>

namespace OpenMeshSkinned {

namespace {

std::string frame_name(size_t f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04zu", f);
  return buf;
}

OpenMesh::MPropHandleT<std::vector<double>> times_handle(SkinnedMesh& mesh) {
  OpenMesh::MPropHandleT<std::vector<double>> h;
  if (!mesh.get_property_handle(h, prop_names::kFrameTimes)) mesh.add_property(h, prop_names::kFrameTimes);
  return h;
}

// Target f - 1 rises from 0 at the previous frame's time to 1 at frame f's and falls to 0 at the next's.
Clip frame_clip_for(const std::vector<double>& times, const std::string& name) {
  Clip clip;
  clip.name = name;
  clip.duration = times.back();
  for (size_t f = 1; f < times.size(); ++f) {
    MorphChannel ch;
    ch.target = int(f - 1);
    ch.times = {times[f - 1], times[f]};
    ch.weights = {0.0, 1.0};
    if (f + 1 < times.size()) {
      ch.times.push_back(times[f + 1]);
      ch.weights.push_back(0.0);
    }
    clip.morph_channels.push_back(std::move(ch));
  }
  return clip;
}

}  // namespace

void set_frame_animation(SkinnedMesh& mesh, const std::vector<FramePositions>& frames, const std::vector<double>& times,
                         const std::string& clip_name) {
  if (frames.size() < 2 || times.size() != frames.size())
    throw std::invalid_argument("a frame animation needs two or more frames, each with a time");
  for (size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != mesh.n_vertices())
      throw std::invalid_argument(frame_name(f) + " has " + std::to_string(frames[f].size()) + " positions, the mesh " +
                                  std::to_string(mesh.n_vertices()) + " vertices");
    if (f > 0 && !(times[f] > times[f - 1])) throw std::invalid_argument("frame times must increase");
  }
  if (!(times[0] >= 0.0)) throw std::invalid_argument("frame times must start at 0 or later");
  auto& targets = morph_targets(mesh);
  targets.clear();
  for (size_t f = 1; f < frames.size(); ++f) targets.push_back({frame_name(f)});
  const auto hd = add_morph_targets(mesh);
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d& p0 = frames[0][vh.idx()];
    mesh.set_point(vh, SkinnedMesh::Point(p0.x(), p0.y(), p0.z()));
    MorphDeltas& d = mesh.property(hd, vh);
    d.resize(frames.size() - 1);
    for (size_t f = 1; f < frames.size(); ++f) d[f - 1] = (frames[f][vh.idx()] - p0).cast<float>();
  }
  set_frame_times(mesh, times, clip_name);
}

void set_frame_times(SkinnedMesh& mesh, const std::vector<double>& times, const std::string& clip_name) {
  if (times.size() < 2 || morph_targets(mesh).size() + 1 != times.size())
    throw std::invalid_argument("a frame animation needs two or more frames, each with a time");
  for (size_t f = 1; f < times.size(); ++f)
    if (!(times[f] > times[f - 1])) throw std::invalid_argument("frame times must increase");
  if (!(times[0] >= 0.0)) throw std::invalid_argument("frame times must start at 0 or later");
  clips(mesh) = {frame_clip_for(times, clip_name)};
  mesh.property(times_handle(mesh)) = times;
}

const std::vector<double>& frame_times(const SkinnedMesh& mesh) {
  static const std::vector<double> none;
  OpenMesh::MPropHandleT<std::vector<double>> h;
  return mesh.get_property_handle(h, prop_names::kFrameTimes) ? mesh.property(h) : none;
}

int frame_clip(const SkinnedMesh& mesh) { return frame_times(mesh).empty() || clips(mesh).empty() ? -1 : 0; }

FramePositions frame_positions(const SkinnedMesh& mesh, size_t f) {
  FramePositions out(mesh.n_vertices());
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  const bool morph = f > 0 && morph_deltas_handle(mesh, hd);
  for (auto vh : mesh.all_vertices()) {
    const auto& p = mesh.point(vh);
    out[vh.idx()] = Eigen::Vector3d(p[0], p[1], p[2]);
    if (morph && f - 1 < mesh.property(hd, vh).size()) out[vh.idx()] += mesh.property(hd, vh)[f - 1].cast<double>();
  }
  return out;
}

void keep_frames(SkinnedMesh& mesh, const std::vector<size_t>& keep) {
  const std::vector<double> times = frame_times(mesh);
  if (keep.size() < 2 || keep[0] != 0) throw std::invalid_argument("keep_frames: frame 0 and one more frame are kept");
  for (size_t i = 1; i < keep.size(); ++i)
    if (!(keep[i] > keep[i - 1] && keep[i] < times.size()))
      throw std::invalid_argument("keep_frames: frames must be sorted stored frames");
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  morph_deltas_handle(mesh, hd);
  for (auto vh : mesh.all_vertices()) {
    MorphDeltas& d = mesh.property(hd, vh);
    MorphDeltas kept;
    for (size_t i = 1; i < keep.size(); ++i) kept.push_back(d[keep[i] - 1]);
    d = std::move(kept);
  }
  std::vector<double> kept_times;
  auto& targets = morph_targets(mesh);
  std::vector<MorphTarget> kept_targets;
  for (size_t i = 0; i < keep.size(); ++i) {
    kept_times.push_back(times[keep[i]]);
    if (i > 0) kept_targets.push_back(targets[keep[i] - 1]);
  }
  targets = std::move(kept_targets);
  const std::string name = clips(mesh).empty() ? "frames" : clips(mesh)[0].name;
  Clip clip = frame_clip_for(kept_times, name);
  clip.duration = std::max(clip.duration, clips(mesh).empty() ? 0.0 : clips(mesh)[0].duration);
  clips(mesh) = {clip};
  mesh.property(times_handle(mesh)) = kept_times;
}

SkinnedMesh bake_frame_animation(const SkinnedMesh& mesh, size_t clip, size_t n_frames) {
  const auto& all = clips(mesh);
  if (clip >= all.size() || n_frames < 2)
    throw std::invalid_argument("bake_frame_animation: no such clip, or < 2 frames");
  const Clip& c = all[clip];
  std::vector<FramePositions> frames;
  std::vector<double> times;
  for (size_t f = 0; f < n_frames; ++f) {
    times.push_back(c.duration * double(f) / double(n_frames - 1));
    frames.push_back(skin_positions(mesh, sample_pose(skeleton(mesh), c, times.back())));
  }
  if (!(c.duration > 0.0))
    for (size_t f = 0; f < n_frames; ++f) times[f] = double(f);
  SkinnedMesh out = mesh;
  const auto h = influences_handle(out);
  for (auto vh : out.vertices()) out.property(h, vh) = Influences::rigid(0);
  set_frame_animation(out, frames, times, c.name);
  example_poses(out) = {Pose::identity(skeleton(out).size())};
  return out;
}

}  // namespace OpenMeshSkinned
