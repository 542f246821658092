#pragma once
/** \file KeyReduction.hh
 *  Motion LoD: fewer key frames in a clip's channels, each removal kept only while the channel between the
 *  keys that remain still passes within a tolerance of every original key (translations and scales
 *  linearly, rotations by slerp, as the clips are played).
 *
 *  Savoye & Meyer (2008, 4.3) merge neighbouring key frames whose distance — the energy to move every joint
 *  from one to the other — is under a threshold. Here each channel is thinned on its own, which also drops
 *  keys where only some joints move, and the threshold is not chosen by hand: reduce_clips_to_error()
 *  picks the largest tolerance whose effect on the skinned surface stays within a bound (beyond the paper).
 */

#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <vector>

namespace OpenMeshSkinned {

/// How far a channel may stray from a dropped key.
struct KeyTolerance {
  double rotation = 0.0;     ///< radians
  double translation = 0.0;  ///< length units of the skeleton's local frames
  double scale = 0.0;        ///< relative
};

/// \p clip with the keys \p tol allows to drop removed (first and last key of every channel kept).
Clip reduce_keys(const Clip& clip, const KeyTolerance& tol);

/** The paper's motion LoD: the clip's key frames (every key time of any channel), each dropped when the
 *  energy to move all joints from the last kept frame to it, and from it to the next frame — sum over
 *  joints of rho(j) times the change of its three Euler angles, over pi, as in joint_energy() — is under
 *  \p threshold (the last frame of a hold stays); the first and last frames stay, so the clip keeps its
 *  duration. Channels keep their keys at the kept frames. */
Clip merge_key_frames(const Clip& clip, const Skeleton& skel, double threshold);

/// How reduce_clips_to_error() drops keys.
enum class KeyReductionMethod {
  Channels,  ///< reduce_keys(): each channel thinned where interpolation reproduces it (default)
  Frames,    ///< merge_key_frames(): the paper's whole-frame merge
};

/// Keys over every channel of \p clips (translation, rotation and scale keys counted separately, and the
/// keys of every morph weight channel).
size_t count_keys(const std::vector<Clip>& clips);

/// Every key time of \p clip's channels and the midpoints between consecutive ones, sorted.
std::vector<double> key_times_and_midpoints(const Clip& clip);

/** \p mesh's clips with as few keys as keep every vertex of \p mesh, posed by the reduced clips, within
 *  \p max_distance of where the full clips put it, at every key time and between keys. The tolerance is
 *  one scale s (rotation s radians, translation s x the skeleton's rest extent, scale s) found by
 *  bisection, the largest that passes (for KeyReductionMethod::Frames, s is the energy threshold). */
template <typename Mesh>
std::vector<Clip> reduce_clips_to_error(const Mesh& mesh, double max_distance,
                                        KeyReductionMethod method = KeyReductionMethod::Channels) {
  const Skeleton& skel = skeleton(mesh);
  const std::vector<Clip>& full = clips(mesh);
  double extent = 0.0;
  for (const Joint& j : skel.joints) extent = std::max(extent, j.rest_local.block<3, 1>(0, 3).norm());
  extent = std::max(extent, 1e-9);
  std::vector<std::vector<double>> times(full.size());
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> reference(full.size());
  for (size_t c = 0; c < full.size(); ++c) {
    times[c] = key_times_and_midpoints(full[c]);
    for (double t : times[c]) reference[c].push_back(skin_positions(mesh, sample_pose(skel, full[c], t)));
  }
  auto reduce = [&](double s) {
    std::vector<Clip> out;
    for (const Clip& c : full)
      out.push_back(method == KeyReductionMethod::Frames ? merge_key_frames(c, skel, s)
                                                         : reduce_keys(c, KeyTolerance{s, s * extent, s}));
    return out;
  };
  auto passes = [&](const std::vector<Clip>& reduced) {
    for (size_t c = 0; c < full.size(); ++c)
      for (size_t i = 0; i < times[c].size(); ++i) {
        const auto posed = skin_positions(mesh, sample_pose(skel, reduced[c], times[c][i]));
        for (size_t v = 0; v < posed.size(); ++v)
          if ((posed[v] - reference[c][i][v]).norm() > max_distance) return false;
      }
    return true;
  };
  double lo = 0.0, hi = 0.5;  // radians; anything coarser is no longer the same motion
  std::vector<Clip> best = full;
  if (auto r = reduce(hi); passes(r)) return r;
  for (int it = 0; it < 12; ++it) {
    const double mid = 0.5 * (lo + hi);
    auto r = reduce(mid);
    if (passes(r)) {
      lo = mid;
      best = std::move(r);
    } else {
      hi = mid;
    }
  }
  return best;
}

}  // namespace OpenMeshSkinned
