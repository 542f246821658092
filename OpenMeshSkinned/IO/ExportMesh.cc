#include "OpenMeshSkinned/IO/ExportParts.hh"

#include "OpenMeshSkinned/IO/ExportCorners.hh"
#include "OpenMeshSkinned/IO/ExportGltf.hh"
#include "OpenMeshSkinned/IO/ExportMaterials.hh"
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <cmath>
#include <map>

namespace OpenMeshSkinned::detail {

namespace {

// What every primitive of the mesh writes alike.
struct MeshLayout {
  const SkinnedMesh& mesh;
  const std::string& path;  // the file, in errors
  OpenMesh::VPropHandleT<Influences> h_inf;
  const std::vector<Material>& mats;
  int slots = 0;  // whole JOINTS_n/WEIGHTS_n sets of four
  bool has_n = false, has_uv = false;
  std::vector<Written> sets;
  std::vector<int> uv_sets;
  OpenMesh::VPropHandleT<float> h_error;
  bool has_error = false;
  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  size_t n_targets = 0;

  MeshLayout(const SkinnedMesh& m, const std::string& p)
      : mesh(m), path(p), h_inf(influences_handle(m)), mats(materials(m)) {}
  IOError fail(const std::string& what) const { return IOError(path + ": " + what); }
};

MeshLayout layout_of(const SkinnedMesh& mesh, const std::string& path) {
  MeshLayout l(mesh, path);
  int max_influences = 1;
  for (auto vh : mesh.vertices()) max_influences = std::max(max_influences, mesh.property(l.h_inf, vh).size());
  if (max_influences > Influences::kCapacity)
    throw l.fail("a vertex has more than " + std::to_string(Influences::kCapacity) + " influences");
  l.slots = 4 * ((max_influences + 3) / 4);
  l.has_n = mesh.has_halfedge_normals();
  l.has_uv = writes_first_uv_set(mesh);
  l.sets = written_sets(mesh, l.has_uv ? 1 : 0);
  l.uv_sets = written_uv_sets(mesh);
  l.has_error = mesh.get_property_handle(l.h_error, kVertexErrorProperty);
  l.n_targets = morph_deltas_handle(mesh, l.h_delta) ? morph_targets(mesh).size() : 0;
  return l;
}

// Faces grouped by material: one primitive each.
std::map<int, std::vector<SkinnedMesh::FaceHandle>> faces_by_material(const SkinnedMesh& mesh) {
  const auto h_fmat = face_material_handle(mesh);
  const auto& mats = materials(mesh);
  std::map<int, std::vector<SkinnedMesh::FaceHandle>> by_material;
  for (auto fh : mesh.faces()) {
    int m = mesh.property(h_fmat, fh);
    if (m < -1 || m >= static_cast<int>(mats.size())) m = -1;
    by_material[m].push_back(fh);
  }
  return by_material;
}

// A primitive's corners with their normals and tangents (empty when it writes none).
struct CornerFrames {
  std::vector<SkinnedMesh::HalfedgeHandle> hehs;
  std::vector<Eigen::Vector3d> normals;
  std::vector<Eigen::Vector4d> tangents;
};

CornerFrames corner_frames(const MeshLayout& l, int mat, const std::vector<SkinnedMesh::FaceHandle>& faces) {
  const SkinnedMesh& mesh = l.mesh;
  const auto rest_point = [&mesh](SkinnedMesh::VertexHandle vh) { return mesh.point(vh); };
  CornerFrames f;
  // Every corner's normal first: a corner's tangent depends on its neighbours'.
  for (auto fh : faces)
    for (auto heh : mesh.fh_range(fh)) {
      f.hehs.push_back(heh);
      f.normals.push_back(l.has_n ? corner_normal(mesh, heh, rest_point) : Eigen::Vector3d::Zero());
    }
  // Tangents where the material's normal map (or what else needs them) reads a UV set that is written;
  // glTF ignores tangents without normals.
  const int tangent_set = l.has_n && mat >= 0 ? tangent_uv_set(l.mats[mat]) : -1;
  if (tangent_set >= 0) {
    const int index = written_uv_index(l.uv_sets, tangent_set);
    const auto source = std::find(l.uv_sets.begin(), l.uv_sets.end(), index);
    if (source != l.uv_sets.end())
      f.tangents = corner_tangents(tangent_corners(mesh, f.hehs, f.normals, int(source - l.uv_sets.begin())));
  }
  return f;
}

Corner corner_at(const MeshLayout& l, const CornerFrames& f, size_t k) {
  const auto heh = f.hehs[k];
  Corner c{l.mesh.to_vertex_handle(heh).idx(), {0, 0, 0}, {0, 0}, {}};
  const Eigen::Vector3d& n = f.normals[k];
  if (l.has_n) c.n = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
  if (!f.tangents.empty()) {
    const Eigen::Vector3f t = f.tangents[k].head<3>().cast<float>().normalized();  // unit in float too
    c.tangent = {t[0], t[1], t[2], static_cast<float>(f.tangents[k][3])};
  }
  if (l.has_uv) {
    auto t = l.mesh.texcoord2D(heh);
    if (!std::isfinite(t[0]) || !std::isfinite(t[1])) t = SkinnedMesh::TexCoord2D(0, 0);
    c.uv = {t[0], 1.0f - t[1]};  // glTF's UV origin is top-left, assimp's bottom-left
  }
  for (const Written& w : l.sets) append_set(w, l.mesh.property(w.channel.handle, heh), c.sets);
  return c;
}

// One primitive's vertex streams, a vertex per distinct corner.
struct PrimitiveStreams {
  std::vector<std::vector<float>> deltas, normal_deltas, set_values;
  std::vector<float> pos, nrm, uv, err, tan;
  std::vector<uint16_t> joints;
  std::vector<float> weights;
  std::vector<uint32_t> indices;
  std::vector<double> mn = std::vector<double>(3, HUGE_VAL), mx = std::vector<double>(3, -HUGE_VAL);
  bool has_tangents = false;
  size_t n_vertices = 0;
};

// Each morph target's offset of the corner's vertex and, when the target has normals, of its normal \p n.
void append_morph_deltas(const MeshLayout& l, SkinnedMesh::HalfedgeHandle heh, const Eigen::Vector3d& n,
                         PrimitiveStreams& s) {
  const SkinnedMesh& mesh = l.mesh;
  const auto vh = mesh.to_vertex_handle(heh);
  for (size_t t = 0; t < l.n_targets; ++t) {
    const MorphDeltas& d = mesh.property(l.h_delta, vh);
    const Eigen::Vector3f x = t < d.size() ? d[t] : Eigen::Vector3f::Zero();
    s.deltas[t].insert(s.deltas[t].end(), {x.x(), x.y(), x.z()});
    if (!l.has_n || !morph_targets(mesh)[t].normals) continue;
    const auto morphed = [&](SkinnedMesh::VertexHandle w) {
      const MorphDeltas& dw = mesh.property(l.h_delta, w);
      const Eigen::Vector3f o = t < dw.size() ? dw[t] : Eigen::Vector3f::Zero();
      return mesh.point(w) + SkinnedMesh::Point(o.x(), o.y(), o.z());
    };
    const Eigen::Vector3d dn = corner_normal(mesh, heh, morphed) - n;
    s.normal_deltas[t].insert(s.normal_deltas[t].end(),
                              {static_cast<float>(dn[0]), static_cast<float>(dn[1]), static_cast<float>(dn[2])});
  }
}

// A new vertex for corner \p c (the corner \p heh, with normal \p n).
void append_vertex(const MeshLayout& l, SkinnedMesh::HalfedgeHandle heh, const Eigen::Vector3d& n, const Corner& c,
                   PrimitiveStreams& s) {
  const SkinnedMesh& mesh = l.mesh;
  const auto vh = mesh.to_vertex_handle(heh);
  const auto p = mesh.point(vh);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    throw l.fail("vertex " + std::to_string(vh.idx()) + " has a non-finite position");
  append_morph_deltas(l, heh, n, s);
  for (int k = 0; k < 3; ++k) {
    const float f = static_cast<float>(p[k]);
    s.pos.push_back(f);
    s.mn[k] = std::min<double>(s.mn[k], f);
    s.mx[k] = std::max<double>(s.mx[k], f);
  }
  if (l.has_error) s.err.push_back(mesh.property(l.h_error, vh));
  s.nrm.insert(s.nrm.end(), c.n.begin(), c.n.end());
  if (s.has_tangents) s.tan.insert(s.tan.end(), c.tangent.begin(), c.tangent.end());
  s.uv.insert(s.uv.end(), c.uv.begin(), c.uv.end());
  for (size_t i = 0, at = 0; i < l.sets.size(); at += l.sets[i].components, ++i)
    s.set_values[i].insert(s.set_values[i].end(), c.sets.begin() + at, c.sets.begin() + at + l.sets[i].components);
  float_weights(mesh.property(l.h_inf, vh), l.slots, s.joints, s.weights);
}

PrimitiveStreams gather_streams(const MeshLayout& l, const CornerFrames& f) {
  PrimitiveStreams s;
  s.deltas.resize(l.n_targets);
  s.normal_deltas.resize(l.n_targets);
  s.set_values.resize(l.sets.size());
  s.has_tangents = !f.tangents.empty();
  std::map<Corner, uint32_t> index_of;
  for (size_t k = 0; k < f.hehs.size(); ++k) {
    const Corner c = corner_at(l, f, k);
    auto [it, inserted] = index_of.emplace(c, static_cast<uint32_t>(index_of.size()));
    if (inserted) append_vertex(l, f.hehs[k], f.normals[k], c, s);
    s.indices.push_back(it->second);
  }
  s.n_vertices = index_of.size();
  return s;
}

int vec_type(int components) {
  return components == 2 ? TINYGLTF_TYPE_VEC2 : components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
}

// JOINTS_n and WEIGHTS_n, four slots each.
void write_skin_sets(const MeshLayout& l, const PrimitiveStreams& s, BufferWriter& buf, tinygltf::Primitive& prim) {
  const size_t nv = s.n_vertices;
  const int slots = l.slots;
  for (int set = 0; set < slots / 4; ++set) {
    std::vector<uint16_t> js;
    std::vector<float> ws;
    for (size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 4; ++k) {
        js.push_back(s.joints[v * slots + set * 4 + k]);
        ws.push_back(s.weights[v * slots + set * 4 + k]);
      }
    const std::string suffix = "_" + std::to_string(set);
    prim.attributes["JOINTS" + suffix] =
        buf.add(js, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["WEIGHTS" + suffix] =
        buf.add(ws, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
}

void write_morph_targets(const MeshLayout& l, const PrimitiveStreams& s, BufferWriter& buf, tinygltf::Primitive& prim) {
  const size_t nv = s.n_vertices;
  for (size_t t = 0; t < l.n_targets; ++t) {
    std::vector<double> dmn(3, HUGE_VAL), dmx(3, -HUGE_VAL);  // the spec requires bounds on POSITION
    for (size_t i = 0; i < s.deltas[t].size(); ++i) {
      dmn[i % 3] = std::min<double>(dmn[i % 3], s.deltas[t][i]);
      dmx[i % 3] = std::max<double>(dmx[i % 3], s.deltas[t][i]);
    }
    prim.targets.push_back({{"POSITION", buf.add(s.deltas[t], TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv,
                                                 TINYGLTF_TARGET_ARRAY_BUFFER, dmn, dmx)}});
    if (!s.normal_deltas[t].empty())
      prim.targets.back()["NORMAL"] = buf.add(s.normal_deltas[t], TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv,
                                              TINYGLTF_TARGET_ARRAY_BUFFER);
  }
}

tinygltf::Primitive write_primitive(const MeshLayout& l, int mat, const PrimitiveStreams& s, BufferWriter& buf) {
  const size_t nv = s.n_vertices;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  if (mat >= 0) prim.material = mat;
  prim.attributes["POSITION"] =
      buf.add(s.pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, s.mn, s.mx);
  if (l.has_n)
    prim.attributes["NORMAL"] =
        buf.add(s.nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (s.has_tangents)
    prim.attributes["TANGENT"] =
        buf.add(s.tan, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (l.has_uv)
    prim.attributes["TEXCOORD_0"] =
        buf.add(s.uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  for (size_t i = 0; i < l.sets.size(); ++i)
    prim.attributes[l.sets[i].attribute] = buf.add(s.set_values[i], TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                   vec_type(l.sets[i].components), nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (l.has_error)
    prim.attributes["_ERROR"] =
        buf.add(s.err, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  write_skin_sets(l, s, buf, prim);
  write_morph_targets(l, s, buf, prim);
  prim.indices = buf.add(s.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, s.indices.size(),
                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  return prim;
}

}  // namespace

tinygltf::Mesh write_mesh(const SkinnedMesh& mesh, BufferWriter& buf, const std::string& path) {
  const auto by_material = faces_by_material(mesh);
  if (by_material.empty()) throw IOError(path + ": mesh has no faces");
  const MeshLayout layout = layout_of(mesh, path);

  tinygltf::Mesh gmesh;
  gmesh.name = "mesh";
  for (const auto& [mat, faces] : by_material) {
    const PrimitiveStreams streams = gather_streams(layout, corner_frames(layout, mat, faces));
    gmesh.primitives.push_back(write_primitive(layout, mat, streams, buf));
  }
  if (layout.n_targets > 0) {
    gmesh.weights.assign(layout.n_targets, 0.0);
    tinygltf::Value::Array names;
    for (const MorphTarget& t : morph_targets(mesh)) names.emplace_back(t.name);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);  // the de-facto convention viewers and DCC tools read
    gmesh.extras = tinygltf::Value(extras);
  }
  return gmesh;
}

}  // namespace OpenMeshSkinned::detail
