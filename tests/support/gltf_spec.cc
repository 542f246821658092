#include "gltf_spec.hh"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

namespace omsk_spec {

tinygltf::Model load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool glb =
      path.size() > 4 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 4) == ".GLB");
  const bool ok =
      glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) throw std::runtime_error(path + ": " + err);
  return model;
}

void save_glb(tinygltf::Model& model, const std::string& path) {
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, true, true, false, true))
    throw std::runtime_error(path + ": cannot be written");
}

int components(const tinygltf::Accessor& acc) {
  switch (acc.type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT4:
      return 16;
  }
  throw std::runtime_error("unsupported accessor type");
}

std::vector<double> read(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& acc = model.accessors.at(index);
  const int nc = components(acc);
  std::vector<double> out(acc.count * nc, 0.0);
  if (acc.bufferView < 0) return out;  // all zeros (sparse accessors are not used by the tests' files)
  const tinygltf::BufferView& view = model.bufferViews.at(acc.bufferView);
  const unsigned char* base = model.buffers.at(view.buffer).data.data() + view.byteOffset + acc.byteOffset;
  const int csize = tinygltf::GetComponentSizeInBytes(acc.componentType);
  const size_t stride = view.byteStride ? view.byteStride : csize * nc;
  for (size_t i = 0; i < acc.count; ++i)
    for (int c = 0; c < nc; ++c) {
      const unsigned char* p = base + i * stride + c * csize;
      double v = 0.0;
      switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
          float f;
          std::memcpy(&f, p, 4);
          v = f;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          v = *p;
          if (acc.normalized) v /= 255.0;
          break;
        // Signed normalised integers (gltfpack writes rotation keys so): max(c / (2^(n-1) - 1), -1).
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
          int8_t b;
          std::memcpy(&b, p, 1);
          v = b;
          if (acc.normalized) v = std::max(v / 127.0, -1.0);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          int16_t s;
          std::memcpy(&s, p, 2);
          v = s;
          if (acc.normalized) v = std::max(v / 32767.0, -1.0);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t s;
          std::memcpy(&s, p, 2);
          v = s;
          if (acc.normalized) v /= 65535.0;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
          uint32_t u;
          std::memcpy(&u, p, 4);
          v = u;
          break;
        }
        default:
          throw std::runtime_error("unsupported component type");
      }
      out[i * nc + c] = v;
    }
  return out;
}

double duration(const tinygltf::Model& model, int anim) {
  double d = 0.0;
  for (const auto& s : model.animations.at(anim).samplers) {
    const auto t = read(model, s.input);
    if (!t.empty()) d = std::max(d, t.back());
  }
  return d;
}

namespace {

struct Trs {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
  Eigen::Vector3d s = Eigen::Vector3d::Ones();
  bool has_matrix = false;
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d matrix() const {
    if (has_matrix) return m;
    Eigen::Matrix4d out = Eigen::Matrix4d::Identity();
    out.topLeftCorner<3, 3>() = r.normalized().toRotationMatrix() * s.asDiagonal();
    out.topRightCorner<3, 1>() = t;
    return out;
  }
};

// The sampler's output at time t, n values per key (the spec's LINEAR, STEP and CUBICSPLINE rules;
// rotations (n == 4 with quat) are slerped under LINEAR).
std::vector<double> sample(const tinygltf::Model& model, const tinygltf::AnimationSampler& s, double t, int n,
                           bool quat) {
  const auto in = read(model, s.input);
  const auto out = read(model, s.output);
  const bool cubic = s.interpolation == "CUBICSPLINE";
  const int per_key = cubic ? 3 * n : n;
  auto value = [&](size_t k) {
    std::vector<double> v(n);
    for (int c = 0; c < n; ++c) v[c] = out[k * per_key + (cubic ? n : 0) + c];
    return v;
  };
  if (t <= in.front() || in.size() == 1) return value(0);
  if (t >= in.back()) return value(in.size() - 1);
  const size_t k = std::upper_bound(in.begin(), in.end(), t) - in.begin() - 1;
  const double dt = in[k + 1] - in[k], u = (t - in[k]) / dt;
  if (s.interpolation == "STEP") return value(k);
  std::vector<double> a = value(k), b = value(k + 1), r(n);
  if (cubic) {
    const double u2 = u * u, u3 = u2 * u;
    for (int c = 0; c < n; ++c) {
      const double bk = out[k * per_key + 2 * n + c] * dt, ak1 = out[(k + 1) * per_key + c] * dt;
      r[c] = (2 * u3 - 3 * u2 + 1) * a[c] + (u3 - 2 * u2 + u) * bk + (-2 * u3 + 3 * u2) * b[c] + (u3 - u2) * ak1;
    }
    return r;
  }
  if (quat) {
    const Eigen::Quaterniond qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
    const Eigen::Quaterniond q = qa.normalized().slerp(u, qb.normalized());
    return {q.x(), q.y(), q.z(), q.w()};
  }
  for (int c = 0; c < n; ++c) r[c] = (1 - u) * a[c] + u * b[c];
  return r;
}

size_t n_targets(const tinygltf::Mesh& m) { return m.primitives.empty() ? 0 : m.primitives[0].targets.size(); }

}  // namespace

Soup pose(const tinygltf::Model& model, int anim, double time) {
  const size_t nn = model.nodes.size();
  std::vector<Trs> local(nn);
  std::vector<std::vector<double>> morph(nn);
  for (size_t i = 0; i < nn; ++i) {
    const auto& n = model.nodes[i];
    Trs& l = local[i];
    if (n.matrix.size() == 16) {
      l.has_matrix = true;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) l.m(r, c) = n.matrix[c * 4 + r];
    }
    if (n.translation.size() == 3) l.t = Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    if (n.rotation.size() == 4) l.r = Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (n.scale.size() == 3) l.s = Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]);
    if (n.mesh >= 0) {
      const auto& m = model.meshes[n.mesh];
      morph[i] = !n.weights.empty() ? n.weights : m.weights;
      morph[i].resize(n_targets(m), 0.0);
    }
  }
  if (anim >= 0) {
    const auto& a = model.animations.at(anim);
    for (const auto& ch : a.channels) {
      const auto& s = a.samplers.at(ch.sampler);
      Trs& l = local.at(ch.target_node);
      if (ch.target_path == "translation") {
        const auto v = sample(model, s, time, 3, false);
        l.t = Eigen::Vector3d(v[0], v[1], v[2]);
      } else if (ch.target_path == "rotation") {
        const auto v = sample(model, s, time, 4, true);
        l.r = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
      } else if (ch.target_path == "scale") {
        const auto v = sample(model, s, time, 3, false);
        l.s = Eigen::Vector3d(v[0], v[1], v[2]);
      } else if (ch.target_path == "weights") {
        morph[ch.target_node] = sample(model, s, time, static_cast<int>(morph[ch.target_node].size()), false);
      }
    }
  }
  std::vector<Eigen::Matrix4d> world(nn, Eigen::Matrix4d::Identity());
  std::vector<char> in_scene(nn, 0);
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  std::function<void(int, const Eigen::Matrix4d&)> visit = [&](int i, const Eigen::Matrix4d& parent) {
    world[i] = parent * local[i].matrix();
    in_scene[i] = 1;
    for (int c : model.nodes[i].children) visit(c, world[i]);
  };
  for (int r : model.scenes.at(scene).nodes) visit(r, Eigen::Matrix4d::Identity());

  Soup soup;
  for (size_t i = 0; i < nn; ++i) {
    const auto& node = model.nodes[i];
    if (!in_scene[i] || node.mesh < 0) continue;
    std::vector<Eigen::Matrix4d> joint_mats;
    if (node.skin >= 0) {
      const auto& skin = model.skins[node.skin];
      std::vector<double> ibm;
      if (skin.inverseBindMatrices >= 0) ibm = read(model, skin.inverseBindMatrices);
      for (size_t k = 0; k < skin.joints.size(); ++k) {
        Eigen::Matrix4d b = Eigen::Matrix4d::Identity();
        if (!ibm.empty())
          for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) b(r, c) = ibm[k * 16 + c * 4 + r];
        joint_mats.push_back(world[skin.joints[k]] * b);
      }
    }
    for (const auto& prim : model.meshes[node.mesh].primitives) {
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
      auto pos = read(model, prim.attributes.at("POSITION"));
      const size_t nv = pos.size() / 3;
      for (size_t t = 0; t < prim.targets.size() && t < morph[i].size(); ++t) {
        auto it = prim.targets[t].find("POSITION");
        if (it == prim.targets[t].end() || morph[i][t] == 0.0) continue;
        const auto d = read(model, it->second);
        for (size_t k = 0; k < pos.size(); ++k) pos[k] += morph[i][t] * d[k];
      }
      std::vector<std::vector<double>> js, ws;
      for (int set = 0; node.skin >= 0; ++set) {
        auto j = prim.attributes.find("JOINTS_" + std::to_string(set));
        auto w = prim.attributes.find("WEIGHTS_" + std::to_string(set));
        if (j == prim.attributes.end() || w == prim.attributes.end()) break;
        js.push_back(read(model, j->second));
        ws.push_back(read(model, w->second));
      }
      const int base = static_cast<int>(soup.points.size());
      const auto tc = prim.attributes.find("TEXCOORD_0");
      const std::vector<double> uv = tc == prim.attributes.end() ? std::vector<double>() : read(model, tc->second);
      soup.has_uv = soup.has_uv || !uv.empty();
      for (size_t v = 0; v < nv; ++v)
        soup.uvs.push_back(uv.size() >= 2 * nv ? Eigen::Vector2d(uv[2 * v], uv[2 * v + 1]) : Eigen::Vector2d::Zero());
      for (size_t v = 0; v < nv; ++v) {
        const Eigen::Vector4d p(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0);
        Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
        if (node.skin < 0) {
          m = world[i];
        } else {
          for (size_t set = 0; set < js.size(); ++set)
            for (int k = 0; k < 4; ++k) {
              const double w = ws[set][4 * v + k];
              if (w != 0.0) m += w * joint_mats.at(static_cast<size_t>(js[set][4 * v + k]));
            }
        }
        soup.points.push_back((m * p).head<3>());
      }
      std::vector<double> idx;
      if (prim.indices >= 0) {
        idx = read(model, prim.indices);
      } else {
        for (size_t v = 0; v < nv; ++v) idx.push_back(static_cast<double>(v));
      }
      for (size_t t = 0; t + 2 < idx.size(); t += 3)
        soup.triangles.push_back({base + int(idx[t]), base + int(idx[t + 1]), base + int(idx[t + 2])});
    }
  }
  return soup;
}

double diagonal(const Soup& s) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (const auto& t : s.triangles)
    for (int i : t) {
      lo = lo.cwiseMin(s.points[i]);
      hi = hi.cwiseMax(s.points[i]);
    }
  return s.triangles.empty() ? 0.0 : (hi - lo).norm();
}

namespace {
std::vector<Eigen::Vector3d> used_points(const Soup& s) {
  std::vector<char> used(s.points.size(), 0);
  for (const auto& t : s.triangles)
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
      for (int i : t) used[i] = 1;
  std::vector<Eigen::Vector3d> out;
  for (size_t i = 0; i < s.points.size(); ++i)
    if (used[i]) out.push_back(s.points[i]);
  return out;
}
}  // namespace

double max_nearest_distance(const Soup& a, const Soup& b) {
  auto pb = used_points(b);
  std::sort(pb.begin(), pb.end(), [](const auto& x, const auto& y) { return x.x() < y.x(); });
  double worst = 0.0;
  for (const Eigen::Vector3d& p : used_points(a)) {
    double best = HUGE_VAL;
    const auto mid = std::lower_bound(pb.begin(), pb.end(), p.x(), [](const auto& q, double x) { return q.x() < x; });
    for (auto it = mid; it != pb.end() && it->x() - p.x() < best; ++it) best = std::min(best, (*it - p).norm());
    for (auto it = mid; it != pb.begin();) {
      --it;
      if (p.x() - it->x() >= best) break;
      best = std::min(best, (*it - p).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace omsk_spec
