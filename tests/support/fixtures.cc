#include "fixtures.hh"

#include "gltf_spec.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

namespace omsk_fixtures {

tinygltf::Model testwuson(const std::string& dir) {
  OpenMeshSkinned::SkinnedMesh mesh;
  OpenMeshSkinned::import_skinned(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", mesh);
  const std::string path = dir + "/testwuson_tidy.glb";
  OpenMeshSkinned::export_gltf(mesh, path);
  return omsk_spec::load(path);
}

int add_accessor(tinygltf::Model& m, const std::vector<float>& data, int type, size_t count) {
  auto& bytes = m.buffers.at(0).data;
  while (bytes.size() % 4) bytes.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bytes.size();
  view.byteLength = data.size() * sizeof(float);
  bytes.resize(bytes.size() + view.byteLength);
  std::memcpy(bytes.data() + view.byteOffset, data.data(), view.byteLength);
  m.bufferViews.push_back(view);
  tinygltf::Accessor acc;
  acc.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  acc.type = type;
  acc.count = count;
  if (type == TINYGLTF_TYPE_VEC3 || type == TINYGLTF_TYPE_SCALAR) {
    const int nc = type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
    acc.minValues.assign(nc, HUGE_VAL);
    acc.maxValues.assign(nc, -HUGE_VAL);
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < nc; ++c) {
        acc.minValues[c] = std::min<double>(acc.minValues[c], data[i * nc + c]);
        acc.maxValues[c] = std::max<double>(acc.maxValues[c], data[i * nc + c]);
      }
  }
  m.accessors.push_back(acc);
  return static_cast<int>(m.accessors.size()) - 1;
}

int add_index_accessor(tinygltf::Model& m, const std::vector<uint32_t>& data) {
  std::vector<float> raw(data.size());
  std::memcpy(raw.data(), data.data(), data.size() * 4);
  const int a = add_accessor(m, raw, TINYGLTF_TYPE_SCALAR, data.size());
  m.accessors[a].componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  m.accessors[a].minValues.clear();
  m.accessors[a].maxValues.clear();
  return a;
}

namespace {

std::vector<float> to_float(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

int find_node(const tinygltf::Model& m, const std::string& name) {
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].name == name) return static_cast<int>(i);
  throw std::runtime_error("fixture: no node " + name);
}

int first_skinned_node(const tinygltf::Model& m) {
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].skin >= 0 && m.nodes[i].mesh >= 0) return static_cast<int>(i);
  throw std::runtime_error("fixture: no skinned mesh node");
}

void set_matrix(tinygltf::Node& n, const Eigen::Matrix4d& mat) {
  n.translation.clear();
  n.rotation.clear();
  n.scale.clear();
  n.matrix.clear();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) n.matrix.push_back(mat(r, c));
}

// The node's parent, or -1 (scene root).
int parent_of(const tinygltf::Model& m, int node) {
  for (size_t i = 0; i < m.nodes.size(); ++i)
    for (int c : m.nodes[i].children)
      if (c == node) return static_cast<int>(i);
  return -1;
}

// A node named \p name carrying a new one-primitive mesh of the same name; returns the node's index.
int add_mesh_node(tinygltf::Model& m, const std::string& name, const tinygltf::Primitive& prim,
                  const std::vector<double>& translation) {
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = name;
  node.mesh = static_cast<int>(m.meshes.size()) - 1;
  node.translation = translation;
  m.nodes.push_back(node);
  return static_cast<int>(m.nodes.size()) - 1;
}

}  // namespace

void wrap_under_rotated_root(tinygltf::Model& m, double degrees_x, double scale) {
  tinygltf::Node root;
  root.name = "Armature";
  const Eigen::Quaterniond q(Eigen::AngleAxisd(degrees_x * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  root.rotation = {q.x(), q.y(), q.z(), q.w()};
  root.scale = {scale, scale, scale};
  tinygltf::Node body;
  body.name = "Body";
  body.translation = {3.0, -2.0, 1.0};  // ignored by the spec for skinned meshes
  auto& scene = m.scenes.at(m.defaultScene >= 0 ? m.defaultScene : 0);
  const int root_i = static_cast<int>(m.nodes.size()), body_i = root_i + 1;
  for (int r : scene.nodes) {
    if (m.nodes[r].skin >= 0)
      body.children.push_back(r);
    else
      root.children.push_back(r);
  }
  root.children.push_back(body_i);
  m.nodes.push_back(root);
  m.nodes.push_back(body);
  scene.nodes = {root_i};
}

void attach_rigid_box(tinygltf::Model& m, const std::string& joint, double size) {
  const double h = 0.5 * size;
  std::vector<float> pos, nrm;
  std::vector<uint32_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const uint32_t base = static_cast<uint32_t>(pos.size() / 3);
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[axis] = sign;
      const Eigen::Vector3d u = Eigen::Vector3d::Unit((axis + 1) % 3), v = Eigen::Vector3d::Unit((axis + 2) % 3);
      for (int k = 0; k < 4; ++k) {
        const double a = (k == 1 || k == 2) ? 1 : -1, b = (k >= 2) ? 1 : -1;
        const Eigen::Vector3d p = h * (n + a * u + b * v) + Eigen::Vector3d(0, size, 0);
        pos.insert(pos.end(), {float(p.x()), float(p.y()), float(p.z())});
        nrm.insert(nrm.end(), {float(n.x()), float(n.y()), float(n.z())});
      }
      if (sign > 0)
        idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else
        idx.insert(idx.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_accessor(m, pos, TINYGLTF_TYPE_VEC3, pos.size() / 3);
  prim.attributes["NORMAL"] = add_accessor(m, nrm, TINYGLTF_TYPE_VEC3, nrm.size() / 3);
  prim.indices = add_index_accessor(m, idx);
  const int node = add_mesh_node(m, "Helmet", prim, {0.0, 0.2 * size, 0.0});
  m.nodes[find_node(m, joint)].children.push_back(node);
}

namespace {

// A copy of \p prim restricted to the triangles \p tris (indices into its vertex arrays), with only the
// vertices they use: exporters write compact primitives, and assimp 5.2 misreads skins of primitives
// that leave vertices unused. \p edit may change the copied POSITION/NORMAL values and JOINTS indices.
tinygltf::Primitive compact_primitive(tinygltf::Model& m, const tinygltf::Primitive& prim,
                                      const std::vector<uint32_t>& tris,
                                      const std::function<void(const std::string&, std::vector<double>&)>& edit) {
  std::vector<int> new_index(m.accessors.at(prim.attributes.at("POSITION")).count, -1);
  std::vector<uint32_t> used, idx;
  for (uint32_t v : tris) {
    if (new_index[v] < 0) new_index[v] = static_cast<int>(used.size()), used.push_back(v);
    idx.push_back(static_cast<uint32_t>(new_index[v]));
  }
  tinygltf::Primitive out = prim;
  out.indices = add_index_accessor(m, idx);
  for (auto& [name, acc] : out.attributes) {
    const tinygltf::Accessor src = m.accessors.at(acc);
    const int nc = omsk_spec::components(src);
    const auto all = omsk_spec::read(m, acc);
    std::vector<double> sub;
    for (uint32_t v : used) sub.insert(sub.end(), all.begin() + v * nc, all.begin() + (v + 1) * nc);
    edit(name, sub);
    if (name.rfind("JOINTS_", 0) == 0) {
      std::vector<uint16_t> j(sub.begin(), sub.end());
      std::vector<float> raw((j.size() * 2 + 3) / 4);
      std::memcpy(raw.data(), j.data(), j.size() * 2);
      acc = add_accessor(m, raw, src.type, used.size());
      m.accessors[acc].componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
      m.accessors[acc].minValues.clear();
      m.accessors[acc].maxValues.clear();
      m.bufferViews[m.accessors[acc].bufferView].byteLength = j.size() * 2;
    } else {
      acc = add_accessor(m, to_float(sub), src.type, used.size());
      if (name != "POSITION") m.accessors[acc].minValues.clear(), m.accessors[acc].maxValues.clear();
    }
  }
  return out;
}

}  // namespace

void split_into_second_skin(tinygltf::Model& m) {
  const int node_a = first_skinned_node(m);
  tinygltf::Primitive& prim_a = m.meshes[m.nodes[node_a].mesh].primitives.at(0);
  const auto idx = omsk_spec::read(m, prim_a.indices);
  const size_t half = (idx.size() / 3 / 2) * 3;
  const std::vector<uint32_t> first(idx.begin(), idx.begin() + half), second(idx.begin() + half, idx.end());

  // The second mesh's vertices live in another frame T; its inverse binds absorb T^-1.
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(0.5, -1.0, 2.0);
  const Eigen::Matrix4d Ti = T.inverse();
  const tinygltf::Skin& skin_a = m.skins.at(m.nodes[node_a].skin);
  const size_t nj = skin_a.joints.size();

  tinygltf::Primitive prim_b =
      compact_primitive(m, prim_a, second, [&](const std::string& name, std::vector<double>& v) {
        const bool pos = name == "POSITION", nrm = name == "NORMAL";
        if (pos || nrm)
          for (size_t i = 0; i + 2 < v.size(); i += 3) {
            const Eigen::Vector3d x(v[i], v[i + 1], v[i + 2]);
            const Eigen::Vector3d y =
                pos ? Eigen::Vector3d((T * x.homogeneous()).head<3>()) : Eigen::Vector3d(T.topLeftCorner<3, 3>() * x);
            v[i] = y.x(), v[i + 1] = y.y(), v[i + 2] = y.z();
          }
        if (name.rfind("JOINTS_", 0) == 0)  // indices into the reversed joint list
          for (double& j : v) j = static_cast<double>(nj - 1 - static_cast<size_t>(j));
      });
  prim_a = compact_primitive(m, prim_a, first, [](const std::string&, std::vector<double>&) {});

  tinygltf::Skin skin_b;
  skin_b.name = "second_skin";
  skin_b.joints.assign(skin_a.joints.rbegin(), skin_a.joints.rend());
  const auto ibm_a = omsk_spec::read(m, skin_a.inverseBindMatrices);
  std::vector<float> ibm_b;
  for (size_t k = 0; k < nj; ++k) {
    const size_t src = nj - 1 - k;
    Eigen::Matrix4d b;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) b(r, c) = ibm_a[src * 16 + c * 4 + r];
    Eigen::Matrix4d nb = b * Ti;
    nb.row(3) << 0, 0, 0, 1;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ibm_b.push_back(static_cast<float>(nb(r, c)));
  }
  skin_b.inverseBindMatrices = add_accessor(m, ibm_b, TINYGLTF_TYPE_MAT4, nj);
  m.skins.push_back(skin_b);
  const int node_b = add_mesh_node(m, "SecondHalf", prim_b, {10.0, 0.0, 0.0});  // translation ignored by the spec
  m.nodes[node_b].skin = static_cast<int>(m.skins.size()) - 1;
  const int parent = parent_of(m, node_a);
  if (parent >= 0)
    m.nodes[parent].children.push_back(node_b);
  else
    m.scenes.at(m.defaultScene >= 0 ? m.defaultScene : 0).nodes.push_back(node_b);
}

void add_morph_target(tinygltf::Model& m) {
  const int node = first_skinned_node(m);
  tinygltf::Mesh& mesh = m.meshes[m.nodes[node].mesh];
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto& prim : mesh.primitives) {
    const auto& acc = m.accessors[prim.attributes.at("POSITION")];
    lo = std::min(lo, acc.minValues.at(1));
    hi = std::max(hi, acc.maxValues.at(1));
  }
  const double top = hi - (hi - lo) / 3.0, amount = 0.05 * (hi - lo);
  for (auto& prim : mesh.primitives) {
    const auto pos = omsk_spec::read(m, prim.attributes.at("POSITION"));
    std::vector<float> delta(pos.size(), 0.0f);
    for (size_t v = 0; v < pos.size() / 3; ++v) {
      if (pos[3 * v + 1] < top) continue;
      const double s = (pos[3 * v + 1] - top) / (hi - top);
      delta[3 * v] = static_cast<float>(amount * s * (pos[3 * v] >= 0 ? 1 : -1));
      delta[3 * v + 1] = static_cast<float>(amount * s);
    }
    prim.targets.push_back({{"POSITION", add_accessor(m, delta, TINYGLTF_TYPE_VEC3, pos.size() / 3)}});
  }
  mesh.weights = {0.0};
  tinygltf::Value::Array names{tinygltf::Value(std::string("Bulge"))};
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(names);
  mesh.extras = tinygltf::Value(extras);
  if (m.animations.empty()) return;
  auto& anim = m.animations[0];
  const double d = omsk_spec::duration(m, 0);
  tinygltf::AnimationSampler s;
  s.input = add_accessor(m, {0.0f, float(d / 2), float(d)}, TINYGLTF_TYPE_SCALAR, 3);
  s.output = add_accessor(m, {0.0f, 1.0f, 0.0f}, TINYGLTF_TYPE_SCALAR, 3);
  s.interpolation = "LINEAR";
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel ch;
  ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
  ch.target_node = node;
  ch.target_path = "weights";
  anim.channels.push_back(ch);
}

void add_degenerate_faces(tinygltf::Model& m) {
  const int node = first_skinned_node(m);
  tinygltf::Primitive& prim = m.meshes[m.nodes[node].mesh].primitives.at(0);
  const auto idx = omsk_spec::read(m, prim.indices);
  std::vector<uint32_t> out(idx.begin(), idx.end());
  for (size_t t = 0; t + 2 < idx.size() && t < 30; t += 3) {
    out.insert(out.end(), {uint32_t(idx[t]), uint32_t(idx[t]), uint32_t(idx[t + 1])});  // repeated index
  }
  out.insert(out.end(), {uint32_t(idx[0]), uint32_t(idx[1]), uint32_t(idx[2])});  // duplicate face
  prim.indices = add_index_accessor(m, out);
}

}  // namespace omsk_fixtures
