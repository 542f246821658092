#include "OpenMeshSkinned/Skin/Skeleton.hh"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {

int Skeleton::find(const std::string& name) const {
  for (int i = 0; i < size(); ++i)
    if (joints[i].name == name) return i;
  return -1;
}

std::vector<Eigen::Matrix4d> Skeleton::globals(const std::vector<Eigen::Matrix4d>& locals) const {
  std::vector<Eigen::Matrix4d> g(joints.size());
  for (size_t i = 0; i < joints.size(); ++i) {
    const int p = joints[i].parent;
    g[i] = p < 0 ? locals[i] : Eigen::Matrix4d(g[p] * locals[i]);
  }
  return g;
}

std::vector<Affine3> Skeleton::skinning(const std::vector<Eigen::Matrix4d>& locals) const {
  const auto g = globals(locals);
  std::vector<Affine3> m(joints.size());
  for (size_t i = 0; i < joints.size(); ++i) m[i] = (g[i] * joints[i].inverse_bind).topRows<3>();
  return m;
}

Pose Pose::identity(int n, std::string label) {
  Pose p;
  p.label = std::move(label);
  p.joint.assign(n, Affine3::Identity());
  return p;
}

bool Pose::finite() const {
  return std::all_of(joint.begin(), joint.end(), [](const Affine3& m) { return m.allFinite(); }) &&
         std::all_of(morph_weights.begin(), morph_weights.end(), [](double w) { return std::isfinite(w); });
}

namespace {

// Index i such that times[i] <= t < times[i+1], and the blend factor between them.
void bracket(const std::vector<double>& times, double t, size_t& i, double& u) {
  if (times.size() == 1 || t <= times.front()) {
    i = 0;
    u = 0.0;
    return;
  }
  if (t >= times.back()) {
    i = times.size() - 2;
    u = 1.0;
    return;
  }
  i = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double dt = times[i + 1] - times[i];
  u = dt > 0.0 ? (t - times[i]) / dt : 0.0;
}

Eigen::Vector3d lerp_keys(const std::vector<double>& times, const std::vector<Eigen::Vector3d>& v, double t) {
  size_t i;
  double u;
  bracket(times, t, i, u);
  if (v.size() == 1) return v[0];
  return (1.0 - u) * v[i] + u * v[i + 1];
}

Eigen::Quaterniond slerp_keys(const std::vector<double>& times, const std::vector<Eigen::Quaterniond>& q, double t) {
  size_t i;
  double u;
  bracket(times, t, i, u);
  if (q.size() == 1) return q[0].normalized();
  // Eigen's slerp takes the shorter arc, as glTF and assimp players do.
  return q[i].normalized().slerp(u, q[i + 1].normalized());
}

}  // namespace

void decompose_trs(const Eigen::Matrix4d& m, Eigen::Vector3d& t, Eigen::Quaterniond& r, Eigen::Vector3d& s) {
  t = m.block<3, 1>(0, 3);
  Eigen::Matrix3d a = m.block<3, 3>(0, 0);
  s = Eigen::Vector3d(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
  if (a.determinant() < 0.0) s.x() = -s.x();
  Eigen::Matrix3d rot = a;
  for (int c = 0; c < 3; ++c)
    if (s[c] != 0.0) rot.col(c) /= s[c];
  // Re-orthonormalise so that small shear or rounding still gives a proper rotation.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(rot, Eigen::ComputeFullU | Eigen::ComputeFullV);
  rot = svd.matrixU() * svd.matrixV().transpose();
  r = Eigen::Quaterniond(rot).normalized();
}

Eigen::Matrix4d compose_trs(const Eigen::Vector3d& t, const Eigen::Quaterniond& r, const Eigen::Vector3d& s) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 3>(0, 0) = r.normalized().toRotationMatrix() * s.asDiagonal();
  m.block<3, 1>(0, 3) = t;
  return m;
}

std::vector<Eigen::Matrix4d> sample_locals(const Skeleton& skel, const Clip& clip, double time) {
  std::vector<Eigen::Matrix4d> locals(skel.joints.size());
  for (size_t i = 0; i < skel.joints.size(); ++i) locals[i] = skel.joints[i].rest_local;
  const double t = std::clamp(time, 0.0, clip.duration);
  for (const Channel& ch : clip.channels) {
    if (ch.joint < 0 || ch.joint >= skel.size()) continue;
    Eigen::Vector3d rt, rs;
    Eigen::Quaterniond rr;
    decompose_trs(skel.joints[ch.joint].rest_local, rt, rr, rs);
    const Eigen::Vector3d tr = ch.translations.empty() ? rt : lerp_keys(ch.translation_times, ch.translations, t);
    const Eigen::Quaterniond ro = ch.rotations.empty() ? rr : slerp_keys(ch.rotation_times, ch.rotations, t);
    const Eigen::Vector3d sc = ch.scales.empty() ? rs : lerp_keys(ch.scale_times, ch.scales, t);
    locals[ch.joint] = compose_trs(tr, ro, sc);
  }
  return locals;
}

std::vector<double> sample_morph_weights(const Clip& clip, double time) {
  std::vector<double> w;
  const double t = std::clamp(time, 0.0, clip.duration);
  for (const MorphChannel& ch : clip.morph_channels) {
    if (ch.target < 0 || ch.times.empty()) continue;
    if (static_cast<int>(w.size()) <= ch.target) w.resize(ch.target + 1, 0.0);
    size_t i;
    double u;
    bracket(ch.times, t, i, u);
    w[ch.target] = ch.weights.size() == 1 ? ch.weights[0] : (1.0 - u) * ch.weights[i] + u * ch.weights[i + 1];
  }
  return w;
}

Pose sample_pose(const Skeleton& skel, const Clip& clip, double time) {
  Pose p;
  p.label = clip.name + "@" + std::to_string(time) + "s";
  p.joint = skel.skinning(sample_locals(skel, clip, time));
  p.morph_weights = sample_morph_weights(clip, time);
  return p;
}

std::vector<Pose> sample_poses_at(const Skeleton& skel, const Clip& clip, const std::vector<double>& times) {
  std::vector<Pose> poses;
  poses.reserve(times.size());
  for (double t : times) poses.push_back(sample_pose(skel, clip, t));
  return poses;
}

std::vector<Pose> sample_poses_evenly(const Skeleton& skel, const Clip& clip, int k) {
  std::vector<double> times;
  for (int i = 0; i < k; ++i) times.push_back(k == 1 ? 0.0 : clip.duration * i / (k - 1));
  return sample_poses_at(skel, clip, times);
}

void add_key_times(const Channel& ch, std::vector<double>& times) {
  for (const auto* v : {&ch.translation_times, &ch.rotation_times, &ch.scale_times})
    times.insert(times.end(), v->begin(), v->end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
}

}  // namespace OpenMeshSkinned
