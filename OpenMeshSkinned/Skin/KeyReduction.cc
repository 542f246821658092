#include "OpenMeshSkinned/Skin/KeyReduction.hh"

#include "OpenMeshSkinned/Skin/SkeletonLod.hh"

#include <algorithm>
#include <cmath>
#include <functional>

namespace OpenMeshSkinned {

namespace {

// Greedy from the left: from the last kept key, extend the span as long as interpolating between its ends
// stays within tolerance of every key inside it; keep the key where it no longer does.
template <typename T>
void thin(std::vector<double>& times, std::vector<T>& values,
          const std::function<T(const T&, const T&, double)>& interpolate,
          const std::function<bool(const T&, const T&)>& close) {
  const size_t n = times.size();
  if (n < 3) return;
  std::vector<size_t> kept = {0};
  size_t anchor = 0;
  for (size_t end = 2; end < n; ++end) {
    bool ok = true;
    for (size_t i = anchor + 1; i < end && ok; ++i) {
      const double u = (times[i] - times[anchor]) / (times[end] - times[anchor]);
      ok = close(interpolate(values[anchor], values[end], u), values[i]);
    }
    if (!ok) {
      anchor = end - 1;
      kept.push_back(anchor);
    }
  }
  kept.push_back(n - 1);
  std::vector<double> t;
  std::vector<T> v;
  for (size_t k : kept) t.push_back(times[k]), v.push_back(values[k]);
  times.swap(t);
  values.swap(v);
}

}  // namespace

Clip reduce_keys(const Clip& clip, const KeyTolerance& tol) {
  Clip out = clip;
  const std::function<Eigen::Vector3d(const Eigen::Vector3d&, const Eigen::Vector3d&, double)> lerp =
      [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double u) -> Eigen::Vector3d { return a + u * (b - a); };
  const std::function<Eigen::Quaterniond(const Eigen::Quaterniond&, const Eigen::Quaterniond&, double)> slerp =
      [](const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double u) {
        return a.normalized().slerp(u, b.normalized());
      };
  for (Channel& ch : out.channels) {
    thin<Eigen::Vector3d>(
        ch.translation_times, ch.translations, lerp,
        [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() <= tol.translation; });
    thin<Eigen::Quaterniond>(ch.rotation_times, ch.rotations, slerp,
                             [&](const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
                               return a.normalized().angularDistance(b.normalized()) <= tol.rotation;
                             });
    thin<Eigen::Vector3d>(ch.scale_times, ch.scales, lerp, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return (a - b).cwiseAbs().maxCoeff() <= tol.scale * std::max(1e-12, b.cwiseAbs().maxCoeff());
    });
  }
  return out;
}

size_t count_keys(const std::vector<Clip>& clips) {
  size_t n = 0;
  for (const Clip& c : clips) {
    for (const Channel& ch : c.channels)
      n += ch.translation_times.size() + ch.rotation_times.size() + ch.scale_times.size();
    for (const MorphChannel& ch : c.morph_channels) n += ch.times.size();
  }
  return n;
}

Clip merge_key_frames(const Clip& clip, const Skeleton& skel, double threshold) {
  std::vector<double> times;
  for (const Channel& ch : clip.channels) add_key_times(ch, times);
  if (times.size() < 3) return clip;
  const std::vector<int> depth = joint_depths(skel);
  const int h = std::max(1, skel.size() ? *std::max_element(depth.begin(), depth.end()) : 1);
  auto rotations = [&](double t) {
    std::vector<Eigen::Matrix3d> r;
    for (const Eigen::Matrix4d& m : sample_locals(skel, clip, t)) r.push_back(m.block<3, 3>(0, 0));
    return r;
  };
  auto energy = [&](const std::vector<Eigen::Matrix3d>& a, const std::vector<Eigen::Matrix3d>& b) {
    double e = 0.0;
    for (size_t j = 0; j < a.size(); ++j) e += double(h - depth[j]) / h * euler_change(a[j], b[j]);
    return e;
  };
  std::vector<double> kept = {times.front()};
  std::vector<Eigen::Matrix3d> last = rotations(times.front()), here = rotations(times[1]);
  for (size_t i = 1; i + 1 < times.size(); ++i) {
    std::vector<Eigen::Matrix3d> next = rotations(times[i + 1]);
    // Merged when close to the last kept frame and to the next one: the last frame of a hold stays, so a
    // run of duplicates goes without changing the motion.
    if (!(energy(last, here) < threshold && energy(here, next) < threshold)) {
      kept.push_back(times[i]);
      last = here;
    }
    here = std::move(next);
  }
  kept.push_back(times.back());
  auto keep = [&](std::vector<double>& t, auto& v) {
    std::vector<double> nt;
    std::remove_reference_t<decltype(v)> nv;
    for (size_t i = 0; i < t.size(); ++i)
      if (i == 0 || i + 1 == t.size() || std::binary_search(kept.begin(), kept.end(), t[i]))
        nt.push_back(t[i]), nv.push_back(v[i]);
    t.swap(nt);
    v.swap(nv);
  };
  Clip out = clip;
  for (Channel& ch : out.channels) {
    keep(ch.translation_times, ch.translations);
    keep(ch.rotation_times, ch.rotations);
    keep(ch.scale_times, ch.scales);
  }
  return out;
}

std::vector<double> key_times_and_midpoints(const Clip& clip) {
  std::vector<double> t;
  for (const Channel& ch : clip.channels) add_key_times(ch, t);
  const size_t n = t.size();
  for (size_t i = 0; i + 1 < n; ++i) t.push_back(0.5 * (t[i] + t[i + 1]));
  std::sort(t.begin(), t.end());
  return t;
}

}  // namespace OpenMeshSkinned
