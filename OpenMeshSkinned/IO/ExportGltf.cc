#include "OpenMeshSkinned/IO/ExportGltf.hh"

#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <unistd.h>

namespace OpenMeshSkinned {
namespace {

// Appends raw bytes to the single buffer and returns an accessor over them.
class BufferWriter {
public:
  explicit BufferWriter(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  /// Appends raw bytes as a buffer view of their own (what images need) and returns its index.
  template <typename T>
  int add_view(const std::vector<T>& data, int target = 0) {
    auto& bytes = model_.buffers[0].data;
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t offset = bytes.size();
    const size_t n = data.size() * sizeof(T);
    bytes.resize(offset + n);
    if (n) std::memcpy(bytes.data() + offset, data.data(), n);

    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = n;
    if (target) view.target = target;
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  template <typename T>
  int add(const std::vector<T>& data, int component_type, int type, size_t count, int target,
          std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor acc;
    acc.bufferView = add_view(data, target);
    acc.componentType = component_type;
    acc.type = type;
    acc.count = count;
    acc.minValues = std::move(min);
    acc.maxValues = std::move(max);
    model_.accessors.push_back(acc);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

private:
  tinygltf::Model& model_;
};

// One glTF vertex: an OpenMesh vertex with one wedge's normal and UV.
struct Corner {
  int vertex;
  std::array<float, 3> n;
  std::array<float, 2> uv;
  bool operator<(const Corner& o) const {
    if (vertex != o.vertex) return vertex < o.vertex;
    if (n != o.n) return n < o.n;
    return uv < o.uv;
  }
};

// Weights in float, made to sum to one in float as glTF validators check it.
void float_weights(const Influences& inf, int slots, std::vector<uint16_t>& joints, std::vector<float>& weights) {
  std::vector<float> w(slots, 0.0f);
  std::vector<uint16_t> j(slots, 0);
  float s = 0.0f;
  for (int i = 0; i < inf.size() && i < slots; ++i) {
    j[i] = static_cast<uint16_t>(inf[i].joint);
    w[i] = static_cast<float>(inf[i].weight);
    s += w[i];
  }
  if (s > 0.0f)
    for (float& x : w) x /= s;
  float rest = 1.0f;
  for (int i = 1; i < slots; ++i) rest -= w[i];
  w[0] = rest;  // the heaviest slot absorbs the rounding
  joints.insert(joints.end(), j.begin(), j.end());
  weights.insert(weights.end(), w.begin(), w.end());
}

// The normal of a corner, recomputed from the geometry as it is now (a LOD's vertices have moved): the
// area-weighted normals of the faces around the vertex whose corner carries a stored normal within 60
// degrees of this corner's, so hard edges and normal seams of the input stay hard.
Eigen::Vector3d corner_normal(const SkinnedMesh& mesh, SkinnedMesh::HalfedgeHandle heh) {
  const auto stored = mesh.normal(heh);
  const Eigen::Vector3d ref(stored[0], stored[1], stored[2]);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto h : mesh.vih_range(mesh.to_vertex_handle(heh))) {
    if (mesh.is_boundary(h)) continue;
    const auto other = mesh.normal(h);
    const Eigen::Vector3d o(other[0], other[1], other[2]);
    if (ref.norm() > 0.0 && o.norm() > 0.0 && o.dot(ref) < 0.5 * o.norm() * ref.norm()) continue;
    // The cross product is the face normal scaled by twice the area: area weighting without normalising
    // a degenerate face's zero vector (which gives NaN).
    const auto p0 = mesh.point(mesh.from_vertex_handle(h)), p1 = mesh.point(mesh.to_vertex_handle(h)),
               p2 = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    const auto c = (p1 - p0) % (p2 - p0);
    sum += Eigen::Vector3d(c[0], c[1], c[2]);
  }
  const double len = sum.norm();
  if (len > 0.0 && std::isfinite(len)) return sum / len;
  const double rlen = ref.norm();
  return rlen > 0.0 && std::isfinite(rlen) ? Eigen::Vector3d(ref / rlen) : Eigen::Vector3d(0.0, 0.0, 1.0);
}

void write_node_trs(tinygltf::Node& node, const Eigen::Matrix4d& local) {
  Eigen::Vector3d t, s;
  Eigen::Quaterniond r;
  decompose_trs(local, t, r, s);
  if (t.squaredNorm() > 0.0) node.translation = {t.x(), t.y(), t.z()};
  if (!r.coeffs().isApprox(Eigen::Vector4d(0, 0, 0, 1))) node.rotation = {r.x(), r.y(), r.z(), r.w()};
  if (!s.isApprox(Eigen::Vector3d::Ones())) node.scale = {s.x(), s.y(), s.z()};
}

}  // namespace

void export_gltf(const SkinnedMesh& mesh, const std::string& path) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".glb" && ext != ".gltf") throw fail("output must end in .glb or .gltf");
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw fail("folder " + dir.string() + " does not exist");
  if (!has_skin(mesh)) throw fail("mesh carries no skin");

  const Skeleton& skel = skeleton(mesh);
  const auto h_inf = influences_handle(mesh);
  const auto h_fmat = face_material_handle(mesh);
  const auto& mats = materials(mesh);
  if (skel.size() == 0) throw fail("skeleton has no joints");
  if (skel.size() > 65535) throw fail("more than 65535 joints");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "OpenMeshSkinned";
  BufferWriter buf(model);

  // Nodes 0..J-1 are the joints, in skeleton order; node J holds the mesh.
  const int n_joints = skel.size();
  for (const Joint& j : skel.joints) {
    tinygltf::Node node;
    // tinygltf writes a node with no name and an identity transform as null, which no reader accepts.
    node.name = j.name.empty() ? "joint" + std::to_string(model.nodes.size()) : j.name;
    write_node_trs(node, j.rest_local);
    model.nodes.push_back(node);
  }
  tinygltf::Scene scene;
  for (int i = 0; i < n_joints; ++i) {
    const int p = skel.joints[i].parent;
    if (p < 0)
      scene.nodes.push_back(i);
    else
      model.nodes[p].children.push_back(i);
  }

  tinygltf::Skin skin;
  skin.name = "skin";
  std::vector<float> ibm;
  for (const Joint& j : skel.joints) {
    if (!j.inverse_bind.allFinite()) throw fail("joint \"" + j.name + "\" has a non-finite inverse bind matrix");
    for (int c = 0; c < 4; ++c) {  // column-major; the last row exactly (0, 0, 0, 1), as the spec requires
      for (int r = 0; r < 3; ++r) ibm.push_back(static_cast<float>(j.inverse_bind(r, c)));
      ibm.push_back(c == 3 ? 1.0f : 0.0f);
    }
  }
  skin.inverseBindMatrices = buf.add(ibm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, n_joints, 0);
  for (int i = 0; i < n_joints; ++i) skin.joints.push_back(i);
  model.skins.push_back(skin);

  for (const Material& m : mats) {
    tinygltf::Material gm;
    gm.name = m.name;
    gm.pbrMetallicRoughness.baseColorFactor = {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]};
    gm.pbrMetallicRoughness.metallicFactor = 0.0;
    if (!m.base_color_image.data.empty()) {
      // Inside the file (a buffer view), so that the LOD carries its textures wherever it goes.
      tinygltf::Image img;
      img.name = m.base_color_image.name;
      img.mimeType = m.base_color_image.mime_type;
      img.bufferView = buf.add_view(m.base_color_image.data);
      model.images.push_back(img);
      tinygltf::Texture tex;
      tex.source = static_cast<int>(model.images.size()) - 1;
      model.textures.push_back(tex);
      gm.pbrMetallicRoughness.baseColorTexture.index = static_cast<int>(model.textures.size()) - 1;
    }
    model.materials.push_back(gm);
  }

  // Faces grouped by material: one primitive each.
  std::map<int, std::vector<SkinnedMesh::FaceHandle>> by_material;
  for (auto fh : mesh.faces()) {
    int m = mesh.property(h_fmat, fh);
    if (m < -1 || m >= static_cast<int>(mats.size())) m = -1;
    by_material[m].push_back(fh);
  }
  if (by_material.empty()) throw fail("mesh has no faces");

  int max_influences = 1;
  for (auto vh : mesh.vertices()) max_influences = std::max(max_influences, mesh.property(h_inf, vh).size());
  if (max_influences > Influences::kCapacity)
    throw fail("a vertex has more than " + std::to_string(Influences::kCapacity) + " influences");
  const int slots = 4 * ((max_influences + 3) / 4);  // whole JOINTS_n/WEIGHTS_n sets of four
  const bool has_n = mesh.has_halfedge_normals();
  const bool has_uv = [&] {
    if (!mesh.has_halfedge_texcoords2D()) return false;
    for (auto heh : mesh.halfedges()) {
      const auto t = mesh.texcoord2D(heh);
      if (std::isfinite(t[0]) && std::isfinite(t[1]) && t != SkinnedMesh::TexCoord2D(0, 0)) return true;
    }
    return false;
  }();

  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  const size_t n_targets = morph_deltas_handle(mesh, h_delta) ? morph_targets(mesh).size() : 0;

  tinygltf::Mesh gmesh;
  gmesh.name = "mesh";
  for (const auto& [mat, faces] : by_material) {
    std::vector<std::vector<float>> deltas(n_targets);
    std::map<Corner, uint32_t> index_of;
    std::vector<float> pos, nrm, uv;
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    std::vector<uint32_t> indices;
    std::vector<double> mn(3, HUGE_VAL), mx(3, -HUGE_VAL);
    for (auto fh : faces) {
      for (auto heh : mesh.fh_range(fh)) {
        const auto vh = mesh.to_vertex_handle(heh);
        Corner c{vh.idx(), {0, 0, 0}, {0, 0}};
        if (has_n) {
          const Eigen::Vector3d n = corner_normal(mesh, heh);
          c.n = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
        }
        if (has_uv) {
          auto t = mesh.texcoord2D(heh);
          if (!std::isfinite(t[0]) || !std::isfinite(t[1])) t = SkinnedMesh::TexCoord2D(0, 0);
          c.uv = {t[0], 1.0f - t[1]};  // glTF's UV origin is top-left, assimp's bottom-left
        }
        auto [it, inserted] = index_of.emplace(c, static_cast<uint32_t>(index_of.size()));
        if (inserted) {
          const auto p = mesh.point(vh);
          if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            throw fail("vertex " + std::to_string(vh.idx()) + " has a non-finite position");
          for (size_t t = 0; t < n_targets; ++t) {
            const MorphDeltas& d = mesh.property(h_delta, vh);
            const Eigen::Vector3f x = t < d.size() ? d[t] : Eigen::Vector3f::Zero();
            deltas[t].insert(deltas[t].end(), {x.x(), x.y(), x.z()});
          }
          for (int k = 0; k < 3; ++k) {
            const float f = static_cast<float>(p[k]);
            pos.push_back(f);
            mn[k] = std::min<double>(mn[k], f);
            mx[k] = std::max<double>(mx[k], f);
          }
          nrm.insert(nrm.end(), c.n.begin(), c.n.end());
          uv.insert(uv.end(), c.uv.begin(), c.uv.end());
          float_weights(mesh.property(h_inf, vh), slots, joints, weights);
        }
        indices.push_back(it->second);
      }
    }
    const size_t nv = index_of.size();
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    if (mat >= 0) prim.material = mat;
    prim.attributes["POSITION"] =
        buf.add(pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, mn, mx);
    if (has_n) prim.attributes["NORMAL"] = buf.add(nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (has_uv) prim.attributes["TEXCOORD_0"] = buf.add(uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    for (int set = 0; set < slots / 4; ++set) {
      std::vector<uint16_t> js;
      std::vector<float> ws;
      for (size_t v = 0; v < nv; ++v)
        for (int k = 0; k < 4; ++k) {
          js.push_back(joints[v * slots + set * 4 + k]);
          ws.push_back(weights[v * slots + set * 4 + k]);
        }
      const std::string suffix = "_" + std::to_string(set);
      prim.attributes["JOINTS" + suffix] =
          buf.add(js, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
      prim.attributes["WEIGHTS" + suffix] =
          buf.add(ws, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    for (size_t t = 0; t < n_targets; ++t) {
      std::vector<double> dmn(3, HUGE_VAL), dmx(3, -HUGE_VAL);  // the spec requires bounds on POSITION
      for (size_t i = 0; i < deltas[t].size(); ++i) {
        dmn[i % 3] = std::min<double>(dmn[i % 3], deltas[t][i]);
        dmx[i % 3] = std::max<double>(dmx[i % 3], deltas[t][i]);
      }
      prim.targets.push_back({{"POSITION", buf.add(deltas[t], TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv,
                                                   TINYGLTF_TARGET_ARRAY_BUFFER, dmn, dmx)}});
    }
    prim.indices = buf.add(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size(),
                           TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    gmesh.primitives.push_back(prim);
  }
  if (n_targets > 0) {
    gmesh.weights.assign(n_targets, 0.0);
    tinygltf::Value::Array names;
    for (const MorphTarget& t : morph_targets(mesh)) names.emplace_back(t.name);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);  // the de-facto convention viewers and DCC tools read
    gmesh.extras = tinygltf::Value(extras);
  }
  model.meshes.push_back(gmesh);

  tinygltf::Node mesh_node;
  mesh_node.name = "skinned_mesh";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  model.nodes.push_back(mesh_node);
  scene.nodes.push_back(n_joints);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  for (const Clip& clip : clips(mesh)) {
    tinygltf::Animation anim;
    anim.name = clip.name;
    auto add_sampler = [&](const std::vector<double>& times, std::vector<float> values, int type, int joint,
                           const char* path_name) {
      if (times.empty()) return;
      std::vector<float> t(times.begin(), times.end());
      const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
      tinygltf::AnimationSampler s;
      s.input = buf.add(t, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, t.size(), 0, {*lo}, {*hi});
      s.output = buf.add(values, TINYGLTF_COMPONENT_TYPE_FLOAT, type, t.size(), 0);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
      ch.target_node = joint;
      ch.target_path = path_name;
      anim.channels.push_back(ch);
    };
    for (const Channel& ch : clip.channels) {
      std::vector<float> tr, ro, sc;
      for (const auto& v : ch.translations) tr.insert(tr.end(), {float(v.x()), float(v.y()), float(v.z())});
      for (const auto& q : ch.rotations) {
        const Eigen::Quaterniond u = q.normalized();
        ro.insert(ro.end(), {float(u.x()), float(u.y()), float(u.z()), float(u.w())});
      }
      for (const auto& v : ch.scales) sc.insert(sc.end(), {float(v.x()), float(v.y()), float(v.z())});
      add_sampler(ch.translation_times, tr, TINYGLTF_TYPE_VEC3, ch.joint, "translation");
      add_sampler(ch.rotation_times, ro, TINYGLTF_TYPE_VEC4, ch.joint, "rotation");
      add_sampler(ch.scale_times, sc, TINYGLTF_TYPE_VEC3, ch.joint, "scale");
    }
    if (n_targets > 0 && !clip.morph_channels.empty()) {
      // glTF animates all of a mesh's weights in one channel: sample every target at the union of the keys.
      std::vector<double> times;
      for (const MorphChannel& mc : clip.morph_channels) times.insert(times.end(), mc.times.begin(), mc.times.end());
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end()), times.end());
      std::vector<float> w;
      for (double t : times) {
        std::vector<double> at = sample_morph_weights(clip, t);
        at.resize(n_targets, 0.0);
        w.insert(w.end(), at.begin(), at.end());
      }
      std::vector<float> tf(times.begin(), times.end());
      tinygltf::AnimationSampler s;
      s.input = buf.add(tf, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, tf.size(), 0, {tf.front()}, {tf.back()});
      s.output = buf.add(w, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, w.size(), 0);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
      ch.target_node = n_joints;  // the mesh node
      ch.target_path = "weights";
      anim.channels.push_back(ch);
    }
    if (!anim.channels.empty()) model.animations.push_back(anim);
  }

  // Write beside the target and rename: readers never see half a file, and a failure leaves nothing.
  const fs::path target(path);
  const fs::path tmp = target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()) + ext);
  tinygltf::TinyGLTF writer;
  const bool binary = ext == ".glb";
  bool ok = false;
  try {
    ok = writer.WriteGltfSceneToFile(&model, tmp.string(), /*embedImages=*/false, /*embedBuffers=*/true,
                                     /*prettyPrint=*/!binary, binary);
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    throw fail(std::string("cannot be written: ") + e.what());
  }
  if (!ok || !fs::exists(tmp, ec) || fs::file_size(tmp, ec) == 0) {
    fs::remove(tmp, ec);
    throw fail("cannot be written (is the folder writable?)");
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw fail("cannot be written: " + ec.message());
  }
}

}  // namespace OpenMeshSkinned
