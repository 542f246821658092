#include "OpenMeshSkinned/IO/InputCheck.hh"

#include "OpenMeshSkinned/IO/PrintableText.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace OpenMeshSkinned {
namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// What is wrong with a value that is written as float, or an empty string when nothing is.
std::string bad_value(double x) {
  if (!std::isfinite(x)) return "the non-finite value " + number(x);
  if (std::abs(x) > kFloatMax) return "the value " + number(x) + ", beyond float range";
  return {};
}

template <typename Derived>
std::string bad_values(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (std::string b = bad_value(m.derived().data()[i]); !b.empty()) return b;
  return {};
}

void check_transform(const Eigen::Matrix4d& m, const std::string& where, const std::string& path) {
  auto fail = [&](const std::string& what) { return IOError(path + ": " + where + " " + what); };
  if (std::string b = bad_values(m); !b.empty()) throw fail("has " + b);
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double size = r.cwiseAbs().maxCoeff();
  if (!(std::abs(r.determinant()) > 1e-12 * size * size * size) || size == 0.0)
    throw fail("is not invertible (a zero scale)");
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6 * std::max(1.0, m.cwiseAbs().maxCoeff()))
    throw fail("is not affine (its last row is not 0 0 0 1)");
}

// What the repairs of one clip came to, said once per clip.
struct Repairs {
  size_t sorted = 0, merged = 0, renormalised = 0;
};

// One key list: checked key by key, then put in time order.
template <typename V, typename CheckValue>
void check_keys(std::vector<double>& times, std::vector<V>& values, const std::string& where, const std::string& path,
                CheckValue check_value, Repairs& rep) {
  auto fail = [&](const std::string& what) { return IOError(path + ": " + where + " " + what); };
  if (times.size() != values.size())
    throw fail("has " + std::to_string(times.size()) + " key times but " + std::to_string(values.size()) + " values");
  for (size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]) || std::abs(times[k]) > kFloatMax)
      throw fail("key " + std::to_string(k) + " has the time " + number(times[k]));
    if (std::string b = check_value(values[k]); !b.empty()) throw fail("key " + std::to_string(k) + " has " + b);
  }
  if (std::is_sorted(times.begin(), times.end())) return;
  std::vector<size_t> order(times.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return times[a] < times[b]; });
  std::vector<double> t2;
  std::vector<V> v2;
  for (size_t i : order) t2.push_back(times[i]), v2.push_back(values[i]);
  times.swap(t2);
  values.swap(v2);
  ++rep.sorted;
}

// Keys whose times are equal once written as float seconds, where glTF needs strictly increasing ones:
// the later of two is kept (the value the clip holds from that time on).
template <typename V>
void merge_equal_times(std::vector<double>& times, std::vector<V>& values, Repairs& rep) {
  size_t kept = 0;
  for (size_t k = 0; k < times.size(); ++k) {
    if (kept > 0 && float(times[k]) <= float(times[kept - 1])) {
      times[kept - 1] = times[k];
      values[kept - 1] = values[k];
      ++rep.merged;
      continue;
    }
    times[kept] = times[k];
    values[kept] = values[k];
    ++kept;
  }
  times.resize(kept);
  values.resize(kept);
}

template <typename F>
void for_each_key_list(Clip& clip, F f) {
  for (Channel& ch : clip.channels) {
    f(ch.translation_times, ch.translations);
    f(ch.rotation_times, ch.rotations);
    f(ch.scale_times, ch.scales);
  }
  for (MorphChannel& mc : clip.morph_channels) f(mc.times, mc.weights);
}

}  // namespace

void check_skeleton(const Skeleton& skel, const std::string& path) {
  for (const Joint& j : skel.joints) {
    check_transform(j.rest_local, "joint \"" + j.name + "\": its rest transform", path);
    check_transform(j.inverse_bind, "joint \"" + j.name + "\": its inverse bind matrix", path);
  }
}

void check_clip(Clip& clip, const Skeleton& skel, size_t n_targets, const std::string& path,
                std::vector<std::string>& warnings) {
  const std::string in_clip = "clip \"" + clip.name + "\":";
  Repairs rep;
  auto vec3 = [](const Eigen::Vector3d& v) { return bad_values(v); };
  for (Channel& ch : clip.channels) {
    if (ch.joint < 0 || ch.joint >= skel.size())
      throw IOError(path + ": " + in_clip + " a channel moves joint " + std::to_string(ch.joint) + " of " +
                    std::to_string(skel.size()));
    const std::string of = in_clip + " joint \"" + skel.joints[ch.joint].name + "\": ";
    check_keys(ch.translation_times, ch.translations, of + "translation", path, vec3, rep);
    check_keys(ch.scale_times, ch.scales, of + "scale", path, vec3, rep);
    check_keys(
        ch.rotation_times, ch.rotations, of + "rotation", path,
        [&rep](Eigen::Quaterniond& q) -> std::string {
          if (std::string b = bad_values(q.coeffs()); !b.empty()) return b;
          const double n = q.norm();
          if (!(n > 1e-12)) return "a rotation of length " + number(n) + ", no quaternion";
          if (std::abs(n - 1.0) > 1e-3) ++rep.renormalised;
          q.normalize();
          return {};
        },
        rep);
  }
  for (MorphChannel& mc : clip.morph_channels) {
    if (mc.target < 0 || size_t(mc.target) >= n_targets)
      throw IOError(path + ": " + in_clip + " a channel moves morph target " + std::to_string(mc.target) + " of " +
                    std::to_string(n_targets));
    check_keys(
        mc.times, mc.weights, in_clip + " morph target " + std::to_string(mc.target) + " weight", path,
        [](double w) { return bad_value(w); }, rep);
  }

  double first = std::numeric_limits<double>::infinity(), last = -first;
  for_each_key_list(clip, [&](std::vector<double>& t, auto&) {
    if (!t.empty()) first = std::min(first, t.front()), last = std::max(last, t.back());
  });
  if (first < 0.0) {
    for_each_key_list(clip, [&](std::vector<double>& t, auto&) {
      for (double& x : t) x -= first;
    });
    warnings.push_back(in_clip + " its keys start at " + number(first) + " s: shifted to start at 0");
    clip.duration -= first;
    last -= first;
    if (last > kFloatMax)
      throw IOError(path + ": " + in_clip + " its keys span " + number(last) + " s, beyond float range");
  }
  for_each_key_list(clip, [&](std::vector<double>& t, auto& v) { merge_equal_times(t, v, rep); });
  if (std::isfinite(last) && (!std::isfinite(clip.duration) || clip.duration < last)) {
    if (!std::isfinite(clip.duration))
      warnings.push_back(in_clip + " its duration " + number(clip.duration) + " is set to its last key, " +
                         number(last) + " s");
    clip.duration = last;
  }
  if (!std::isfinite(clip.duration) || clip.duration < 0.0) clip.duration = 0.0;
  if (rep.sorted > 0)
    warnings.push_back(in_clip + " " + std::to_string(rep.sorted) + " key lists out of time order: sorted");
  if (rep.merged > 0)
    warnings.push_back(in_clip + " " + std::to_string(rep.merged) +
                       " keys fell on the time of the key before them once written as float seconds: merged (the "
                       "later kept)");
  if (rep.renormalised > 0)
    warnings.push_back(in_clip + " " + std::to_string(rep.renormalised) +
                       " rotation keys were not unit quaternions: renormalised");
}

void check_input(SkinnedMesh& mesh, const std::string& path, std::vector<std::string>& warnings) {
  // Names go into glTF's JSON, which must be UTF-8, and into messages on a terminal.
  size_t renamed = 0;
  auto clean = [&renamed](std::string& name) {
    if (std::string p = printable_text(name); p != name) name = std::move(p), ++renamed;
  };
  for (Joint& j : skeleton(mesh).joints) clean(j.name);
  for (Clip& c : clips(mesh)) clean(c.name);
  for (MorphTarget& t : morph_targets(mesh)) clean(t.name);
  for (Material& m : materials(mesh)) clean(m.name);
  if (renamed > 0)
    warnings.push_back(std::to_string(renamed) + " names were not printable UTF-8: their other bytes became '?'");
  // glTF allows base colours in [0, 1] only (other readers' colours can be anything).
  for (Material& m : materials(mesh)) {
    bool clamped = false;
    for (double& c : m.base_color) {
      const double was = c;
      c = std::isfinite(c) ? std::clamp(c, 0.0, 1.0) : 1.0;
      clamped |= c != was;
    }
    if (clamped)
      warnings.push_back("material \"" + m.name +
                         "\": a base colour component outside [0, 1]: clamped (1 where it was not a number)");
  }
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    for (int c = 0; c < 3; ++c)
      if (std::string b = bad_value(p[c]); !b.empty())
        throw IOError(path + ": vertex " + std::to_string(vh.idx()) + " has " + b + " in its position");
  }
  const Skeleton& skel = skeleton(mesh);
  check_skeleton(skel, path);
  const size_t n_targets = morph_targets(mesh).size();
  for (Clip& clip : clips(mesh)) check_clip(clip, skel, n_targets, path, warnings);
}

}  // namespace OpenMeshSkinned
