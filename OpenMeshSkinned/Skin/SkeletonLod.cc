#include "OpenMeshSkinned/Skin/SkeletonLod.hh"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace OpenMeshSkinned {

namespace {

std::vector<int> child_counts(const Skeleton& skel) {
  std::vector<int> c(skel.size(), 0);
  for (const Joint& j : skel.joints)
    if (j.parent >= 0) ++c[j.parent];
  return c;
}

// Minor joints under the energy threshold go first, then the cheapest minor joint until at most
// \p max_joints are left (or no minor joint is).
std::vector<char> removed_joints(const Skeleton& skel, const std::vector<JointLabel>& labels,
                                 const std::vector<double>& energy, int max_joints, const JointRemovalCost& cost,
                                 double energy_threshold) {
  const int n = skel.size();
  std::vector<char> removed(n, 0);
  auto kept_ancestor = [&](int j) {
    int p = skel.joints[j].parent;
    while (p >= 0 && removed[p]) p = skel.joints[p].parent;
    return p;
  };
  int count = n;
  for (int j = 0; j < n; ++j)
    if (labels[j] == JointLabel::Minor && energy[j] < energy_threshold) removed[j] = 1, --count;
  while (count > max_joints) {
    int best = -1;
    double best_cost = 0.0;
    for (int j = 0; j < n; ++j) {
      if (removed[j] || labels[j] != JointLabel::Minor) continue;
      const double c = cost ? cost(j, kept_ancestor(j)) : energy[j];
      if (best < 0 || c < best_cost) best = j, best_cost = c;
    }
    if (best < 0) break;
    removed[best] = 1;
    --count;
  }
  return removed;
}

// The kept joints, each with the rest transforms of the removed ones above it baked in; fills \p r's
// skeleton, new_index and heir. Returns, per kept joint, the chain of removed joints between it and its
// new parent, outermost first.
std::vector<std::vector<int>> keep_joints(const Skeleton& skel, const std::vector<char>& removed,
                                          SkeletonReduction& r) {
  const int n = skel.size();
  r.new_index.assign(n, -1);
  r.heir.assign(n, -1);
  std::vector<std::vector<int>> baked(n);
  for (int j = 0; j < n; ++j) {
    int p = skel.joints[j].parent;
    std::vector<int> chain;
    while (p >= 0 && removed[p]) {
      chain.push_back(p);
      p = skel.joints[p].parent;
    }
    std::reverse(chain.begin(), chain.end());
    if (removed[j]) {
      r.heir[j] = p;  // nearest kept ancestor (-1 only for a removed root, which minor joints never are)
      continue;
    }
    r.heir[j] = j;
    Joint k = skel.joints[j];
    k.parent = p < 0 ? -1 : r.new_index[p];
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) k.rest_local = skel.joints[*it].rest_local * k.rest_local;
    r.new_index[j] = r.skeleton.size();
    r.skeleton.joints.push_back(k);
    baked[j] = chain;
  }
  return baked;
}

// Joint \p j's channel with the removed joints of \p chain above it: keyed at the key times of all of
// them, each key the product of their locals.
Channel baked_channel(const Skeleton& skel, const Clip& clip, int j, const std::vector<int>& chain,
                      const std::vector<const Channel*>& of, int new_index) {
  std::vector<double> times;
  for (int x : chain)
    if (of[x]) add_key_times(*of[x], times);
  if (of[j]) add_key_times(*of[j], times);
  Channel ch;
  ch.joint = new_index;
  for (double t : times) {
    const std::vector<Eigen::Matrix4d> locals = sample_locals(skel, clip, t);
    Eigen::Matrix4d m = locals[j];
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) m = locals[*it] * m;
    Eigen::Vector3d tr, sc;
    Eigen::Quaterniond ro;
    decompose_trs(m, tr, ro, sc);
    ch.translation_times.push_back(t);
    ch.translations.push_back(tr);
    ch.rotation_times.push_back(t);
    ch.rotations.push_back(ro);
    ch.scale_times.push_back(t);
    ch.scales.push_back(sc);
  }
  return ch;
}

Clip reduced_clip(const Skeleton& skel, const Clip& clip, const std::vector<char>& removed,
                  const std::vector<std::vector<int>>& baked, const std::vector<int>& new_index) {
  const int n = skel.size();
  Clip out;
  out.name = clip.name;
  out.duration = clip.duration;
  out.morph_channels = clip.morph_channels;
  std::vector<const Channel*> of(n, nullptr);
  for (const Channel& ch : clip.channels)
    if (ch.joint >= 0 && ch.joint < n) of[ch.joint] = &ch;
  for (int j = 0; j < n; ++j) {
    if (removed[j]) continue;
    bool animated = of[j] != nullptr;
    for (int b : baked[j]) animated |= of[b] != nullptr;
    if (!animated) continue;
    if (baked[j].empty()) {  // its parent is kept: the channel as it was
      Channel ch = *of[j];
      ch.joint = new_index[j];
      out.channels.push_back(ch);
      continue;
    }
    out.channels.push_back(baked_channel(skel, clip, j, baked[j], of, new_index[j]));
  }
  return out;
}

}  // namespace

std::vector<int> joint_depths(const Skeleton& skel) {
  std::vector<int> d(skel.size(), 0);
  for (int j = 0; j < skel.size(); ++j)
    if (skel.joints[j].parent >= 0) d[j] = d[skel.joints[j].parent] + 1;  // parents come first
  return d;
}

double euler_change(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Vector3d ea = a.eulerAngles(0, 1, 2), eb = b.eulerAngles(0, 1, 2);
  double change = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::abs(eb[k] - ea[k]);
    change += std::min(d, 2.0 * M_PI - d);  // the short way round
  }
  return change / M_PI;
}

std::vector<JointLabel> label_joints(const Skeleton& skel) {
  const int n = skel.size();
  const std::vector<int> d = joint_depths(skel), children = child_counts(skel);
  double avg_ngb = 0.0, avg_depth = 0.0;
  for (int j = 0; j < n; ++j) {
    avg_ngb += children[j] + (skel.joints[j].parent >= 0 ? 1 : 0);
    avg_depth += d[j];
  }
  avg_ngb /= std::max(n, 1);
  avg_depth /= std::max(n, 1);
  std::vector<JointLabel> out(n, JointLabel::Minor);
  for (int j = 0; j < n; ++j) {
    const int ngb = children[j] + (skel.joints[j].parent >= 0 ? 1 : 0);
    if (d[j] == 0)
      out[j] = JointLabel::Root;
    else if (children[j] == 0)
      out[j] = JointLabel::EndEffector;
    else if (ngb > 1.9 * avg_ngb && d[j] < avg_depth)
      out[j] = JointLabel::Major;
    else if (ngb > 1.9 * avg_ngb && d[j] > avg_depth)
      out[j] = JointLabel::Extreme;
  }
  return out;
}

std::vector<double> joint_energy(const Skeleton& skel, const std::vector<Clip>& clips) {
  const std::vector<int> d = joint_depths(skel);
  const int h = std::max(1, *std::max_element(d.begin(), d.end()));
  std::vector<double> e(skel.size(), 0.0);
  for (const Clip& clip : clips)
    for (const Channel& ch : clip.channels) {
      if (ch.joint < 0 || ch.joint >= skel.size()) continue;
      double variation = 0.0;
      for (size_t b = 0; b + 1 < ch.rotations.size(); ++b)
        variation += euler_change(ch.rotations[b].normalized().toRotationMatrix(),
                                  ch.rotations[b + 1].normalized().toRotationMatrix());
      e[ch.joint] += double(h - d[ch.joint]) / h * variation;
    }
  return e;
}

SkeletonReduction reduce_skeleton(const Skeleton& skel, const std::vector<Clip>& clips, int max_joints,
                                  const JointRemovalCost& cost, double energy_threshold) {
  const std::vector<JointLabel> labels = label_joints(skel);
  const std::vector<double> energy = joint_energy(skel, clips);
  const std::vector<char> removed = removed_joints(skel, labels, energy, max_joints, cost, energy_threshold);
  SkeletonReduction r;
  const std::vector<std::vector<int>> baked = keep_joints(skel, removed, r);
  for (const Clip& clip : clips) r.clips.push_back(reduced_clip(skel, clip, removed, baked, r.new_index));
  return r;
}

}  // namespace OpenMeshSkinned
