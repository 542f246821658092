#include "OpenMeshSkinned/IO/ExportParts.hh"

#include "OpenMeshSkinned/IO/ExportGltf.hh"
#include "OpenMeshSkinned/IO/ExportMaterials.hh"
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Mesh/Tangents.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace OpenMeshSkinned::detail {

namespace {

// One glTF vertex: an OpenMesh vertex with one wedge's normal, UV, further sets (CornerAttributes.hh) and
// tangent (zero in primitives without one).
struct Corner {
  int vertex;
  std::array<float, 3> n;
  std::array<float, 2> uv;
  std::vector<float> sets;  // each carried set's components, in corner_channels() order
  std::array<float, 4> tangent = {0, 0, 0, 0};
  bool operator<(const Corner& o) const {
    if (vertex != o.vertex) return vertex < o.vertex;
    if (n != o.n) return n < o.n;
    if (uv != o.uv) return uv < o.uv;
    if (sets != o.sets) return sets < o.sets;
    return tangent < o.tangent;
  }
};

// A carried set as written: its attribute name and how many components each vertex has.
struct Written {
  CornerChannel channel;
  std::string attribute;
  int components;
};

// TEXCOORD_n and COLOR_n must be numbered 0, 1, ... without gaps: sets are renumbered in order (UV sets
// from \p first_uv, after TEXCOORD_0 when it is written). Colours are VEC4, or VEC3 when every alpha is 1
// (as assimp reports RGB colours), which says the same thing in less space.
std::vector<Written> written_sets(const SkinnedMesh& mesh, int first_uv) {
  std::vector<Written> out;
  int n_uv = first_uv, n_color = 0;
  for (const CornerChannel& c : corner_channels(mesh)) {
    if (c.kind == CornerKind::TexCoord) {
      out.push_back({c, "TEXCOORD_" + std::to_string(n_uv++), 2});
      continue;
    }
    bool alpha = false;
    for (auto heh : mesh.halfedges())
      if (!mesh.is_boundary(heh) && mesh.property(c.handle, heh)[3] != 1.0f) alpha = true;
    out.push_back({c, "COLOR_" + std::to_string(n_color++), alpha ? 4 : 3});
  }
  return out;
}

// A set's value as written: UVs flipped to glTF's top-left origin like TEXCOORD_0, colours within [0, 1]
// (interpolation can round a hair past 1), anything non-finite as the set's fallback.
void append_set(const Written& w, OpenMesh::Vec4f x, std::vector<float>& out) {
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(x[k])) x = w.channel.fallback();
  if (w.channel.kind == CornerKind::TexCoord) {
    out.insert(out.end(), {x[0], 1.0f - x[1]});
    return;
  }
  for (int k = 0; k < w.components; ++k) out.push_back(std::clamp(x[k], 0.0f, 1.0f));
}

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
// degrees of this corner's, so hard edges and normal seams of the input stay hard. \p point gives each
// vertex's position: the rest position, or a morph target's.
template <typename PointOf>
Eigen::Vector3d corner_normal(const SkinnedMesh& mesh, SkinnedMesh::HalfedgeHandle heh, const PointOf& point) {
  const auto stored = mesh.normal(heh);
  const Eigen::Vector3d ref(stored[0], stored[1], stored[2]);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto h : mesh.vih_range(mesh.to_vertex_handle(heh))) {
    if (mesh.is_boundary(h)) continue;
    const auto other = mesh.normal(h);
    const Eigen::Vector3d o(other[0], other[1], other[2]);
    if (ref.norm() > 0.0 && o.norm() > 0.0 && o.dot(ref) < kHardEdgeNormalCos * o.norm() * ref.norm()) continue;
    // The cross product is the face normal scaled by twice the area: area weighting without normalising
    // a degenerate face's zero vector (which gives NaN).
    const SkinnedMesh::Point p0 = point(mesh.from_vertex_handle(h)), p1 = point(mesh.to_vertex_handle(h)),
                             p2 = point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    const auto c = (p1 - p0) % (p2 - p0);
    sum += Eigen::Vector3d(c[0], c[1], c[2]);
  }
  const double len = sum.norm();
  if (len > 0.0 && std::isfinite(len)) return sum / len;
  const double rlen = ref.norm();
  return rlen > 0.0 && std::isfinite(rlen) ? Eigen::Vector3d(ref / rlen) : Eigen::Vector3d(0.0, 0.0, 1.0);
}

// The normal map's UVs of a primitive's corners (the input's UV set \p set, origin bottom-left as the mesh
// keeps them), their written normals and positions, as the tangent generator takes them.
std::vector<TangentCorner> tangent_corners(const SkinnedMesh& mesh,
                                           const std::vector<SkinnedMesh::HalfedgeHandle>& hehs,
                                           const std::vector<Eigen::Vector3d>& normals, int set) {
  CornerChannel channel{CornerKind::TexCoord, set, OpenMesh::HPropHandleT<OpenMesh::Vec4f>()};
  if (set > 0) mesh.get_property_handle(channel.handle, corner_property_name(CornerKind::TexCoord, set));
  std::vector<TangentCorner> out;
  for (size_t k = 0; k < hehs.size(); ++k) {
    const auto vh = mesh.to_vertex_handle(hehs[k]);
    const auto p = mesh.point(vh);
    Eigen::Vector2d uv(0, 0);
    if (set == 0) {
      const auto t = mesh.texcoord2D(hehs[k]);
      if (std::isfinite(t[0]) && std::isfinite(t[1])) uv = Eigen::Vector2d(t[0], t[1]);
    } else {
      const auto t = mesh.property(channel.handle, hehs[k]);
      if (std::isfinite(t[0]) && std::isfinite(t[1])) uv = Eigen::Vector2d(t[0], t[1]);
    }
    // The normal as written (in float), so that corners written as one vertex share one tangent.
    const Eigen::Vector3d n = normals[k].cast<float>().cast<double>();
    out.push_back({vh.idx(), Eigen::Vector3d(p[0], p[1], p[2]), n, uv});
  }
  return out;
}

}  // namespace

bool writes_first_uv_set(const SkinnedMesh& mesh) {
  if (!mesh.has_halfedge_texcoords2D()) return false;
  // TEXCOORD_1 needs a TEXCOORD_0, zero or not, and so does a textured material (a file whose textures
  // have no UVs to read would otherwise become one the validator refuses).
  for (const CornerChannel& c : corner_channels(mesh))
    if (c.kind == CornerKind::TexCoord) return true;
  for (const Material& m : materials(mesh))
    if (!m.textures.empty()) return true;
  for (auto heh : mesh.halfedges()) {
    if (mesh.is_boundary(heh)) continue;  // no face, no corner: its UV is never set
    const auto t = mesh.texcoord2D(heh);
    if (std::isfinite(t[0]) && std::isfinite(t[1]) && t != SkinnedMesh::TexCoord2D(0, 0)) return true;
  }
  return false;
}

std::vector<int> written_uv_sets(const SkinnedMesh& mesh) {
  std::vector<int> out(kMaxTexCoordSets, -1);
  int next = 0;
  if (writes_first_uv_set(mesh)) out[0] = next++;
  for (const CornerChannel& c : corner_channels(mesh))
    if (c.kind == CornerKind::TexCoord) out[c.set] = next++;
  return out;
}

int written_uv_index(const std::vector<int>& written, int set) {
  return set >= 0 && size_t(set) < written.size() && written[set] >= 0 ? written[set] : 0;
}

tinygltf::Mesh write_mesh(const SkinnedMesh& mesh, BufferWriter& buf, const std::string& path) {
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  const auto h_inf = influences_handle(mesh);
  const auto h_fmat = face_material_handle(mesh);
  const auto& mats = materials(mesh);
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
  const bool has_uv = writes_first_uv_set(mesh);
  const std::vector<Written> sets = written_sets(mesh, has_uv ? 1 : 0);
  const std::vector<int> uv_sets = written_uv_sets(mesh);

  OpenMesh::VPropHandleT<float> h_error;
  const bool has_error = mesh.get_property_handle(h_error, kVertexErrorProperty);

  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  const size_t n_targets = morph_deltas_handle(mesh, h_delta) ? morph_targets(mesh).size() : 0;
  const auto rest_point = [&mesh](SkinnedMesh::VertexHandle vh) { return mesh.point(vh); };

  tinygltf::Mesh gmesh;
  gmesh.name = "mesh";
  for (const auto& [mat, faces] : by_material) {
    std::vector<std::vector<float>> deltas(n_targets), normal_deltas(n_targets);
    std::vector<std::vector<float>> set_values(sets.size());
    std::map<Corner, uint32_t> index_of;
    std::vector<float> pos, nrm, uv, err;
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    std::vector<uint32_t> indices;
    std::vector<double> mn(3, HUGE_VAL), mx(3, -HUGE_VAL);
    // Every corner's normal first: a corner's tangent depends on its neighbours'.
    std::vector<SkinnedMesh::HalfedgeHandle> hehs;
    std::vector<Eigen::Vector3d> normals;
    for (auto fh : faces)
      for (auto heh : mesh.fh_range(fh)) {
        hehs.push_back(heh);
        normals.push_back(has_n ? corner_normal(mesh, heh, rest_point) : Eigen::Vector3d::Zero());
      }
    // Tangents where the material's normal map (or what else needs them) reads a UV set that is written;
    // glTF ignores tangents without normals.
    std::vector<Eigen::Vector4d> tangents;
    const int tangent_set = has_n && mat >= 0 ? tangent_uv_set(mats[mat]) : -1;
    if (tangent_set >= 0) {
      const int index = written_uv_index(uv_sets, tangent_set);
      const auto source = std::find(uv_sets.begin(), uv_sets.end(), index);
      if (source != uv_sets.end())
        tangents = corner_tangents(tangent_corners(mesh, hehs, normals, int(source - uv_sets.begin())));
    }
    std::vector<float> tan;
    for (size_t k = 0; k < hehs.size(); ++k) {
      const auto heh = hehs[k];
      const auto vh = mesh.to_vertex_handle(heh);
      Corner c{vh.idx(), {0, 0, 0}, {0, 0}, {}};
      const Eigen::Vector3d& n = normals[k];
      if (has_n) c.n = {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
      if (!tangents.empty()) {
        const Eigen::Vector3f t = tangents[k].head<3>().cast<float>().normalized();  // unit in float too
        c.tangent = {t[0], t[1], t[2], static_cast<float>(tangents[k][3])};
      }
      if (has_uv) {
        auto t = mesh.texcoord2D(heh);
        if (!std::isfinite(t[0]) || !std::isfinite(t[1])) t = SkinnedMesh::TexCoord2D(0, 0);
        c.uv = {t[0], 1.0f - t[1]};  // glTF's UV origin is top-left, assimp's bottom-left
      }
      for (const Written& w : sets) append_set(w, mesh.property(w.channel.handle, heh), c.sets);
      auto [it, inserted] = index_of.emplace(c, static_cast<uint32_t>(index_of.size()));
      if (inserted) {
        const auto p = mesh.point(vh);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
          throw fail("vertex " + std::to_string(vh.idx()) + " has a non-finite position");
        for (size_t t = 0; t < n_targets; ++t) {
          const MorphDeltas& d = mesh.property(h_delta, vh);
          const Eigen::Vector3f x = t < d.size() ? d[t] : Eigen::Vector3f::Zero();
          deltas[t].insert(deltas[t].end(), {x.x(), x.y(), x.z()});
          if (!has_n || !morph_targets(mesh)[t].normals) continue;
          const auto morphed = [&](SkinnedMesh::VertexHandle w) {
            const MorphDeltas& dw = mesh.property(h_delta, w);
            const Eigen::Vector3f o = t < dw.size() ? dw[t] : Eigen::Vector3f::Zero();
            return mesh.point(w) + SkinnedMesh::Point(o.x(), o.y(), o.z());
          };
          const Eigen::Vector3d dn = corner_normal(mesh, heh, morphed) - n;
          normal_deltas[t].insert(normal_deltas[t].end(),
                                  {static_cast<float>(dn[0]), static_cast<float>(dn[1]), static_cast<float>(dn[2])});
        }
        for (int k = 0; k < 3; ++k) {
          const float f = static_cast<float>(p[k]);
          pos.push_back(f);
          mn[k] = std::min<double>(mn[k], f);
          mx[k] = std::max<double>(mx[k], f);
        }
        if (has_error) err.push_back(mesh.property(h_error, vh));
        nrm.insert(nrm.end(), c.n.begin(), c.n.end());
        if (!tangents.empty()) tan.insert(tan.end(), c.tangent.begin(), c.tangent.end());
        uv.insert(uv.end(), c.uv.begin(), c.uv.end());
        for (size_t i = 0, at = 0; i < sets.size(); at += sets[i].components, ++i)
          set_values[i].insert(set_values[i].end(), c.sets.begin() + at, c.sets.begin() + at + sets[i].components);
        float_weights(mesh.property(h_inf, vh), slots, joints, weights);
      }
      indices.push_back(it->second);
    }
    const size_t nv = index_of.size();
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    if (mat >= 0) prim.material = mat;
    prim.attributes["POSITION"] =
        buf.add(pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER, mn, mx);
    if (has_n)
      prim.attributes["NORMAL"] =
          buf.add(nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!tangents.empty())
      prim.attributes["TANGENT"] =
          buf.add(tan, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (has_uv)
      prim.attributes["TEXCOORD_0"] =
          buf.add(uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    for (size_t i = 0; i < sets.size(); ++i)
      prim.attributes[sets[i].attribute] = buf.add(set_values[i], TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                   sets[i].components == 2   ? TINYGLTF_TYPE_VEC2
                                                   : sets[i].components == 3 ? TINYGLTF_TYPE_VEC3
                                                                             : TINYGLTF_TYPE_VEC4,
                                                   nv, TINYGLTF_TARGET_ARRAY_BUFFER);
    if (has_error)
      prim.attributes["_ERROR"] =
          buf.add(err, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
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
      if (!normal_deltas[t].empty())
        prim.targets.back()["NORMAL"] = buf.add(normal_deltas[t], TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nv,
                                                TINYGLTF_TARGET_ARRAY_BUFFER);
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
  return gmesh;
}

}  // namespace OpenMeshSkinned::detail
