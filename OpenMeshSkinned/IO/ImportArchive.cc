#include "OpenMeshSkinned/IO/ImportArchive.hh"

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <cereal/archives/binary.hpp>
#include <cereal/types/array.hpp>
#include <cereal/types/memory.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/vector.hpp>

#include <algorithm>
#include <cstdint>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <streambuf>

// Fixed-size Eigen types as raw bytes: both ends are the same build on the same machine.
namespace cereal {
template <class Ar, typename S, int R, int C, int O, int MR, int MC>
void serialize(Ar& ar, Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  static_assert(R > 0 && C > 0, "fixed-size matrices only");
  ar(binary_data(m.data(), sizeof(S) * R * C));
}
template <class Ar>
void serialize(Ar& ar, Eigen::Quaterniond& q) {
  ar(binary_data(q.coeffs().data(), sizeof(double) * 4));
}
}  // namespace cereal

namespace OpenMeshSkinned {

template <class Ar>
void serialize(Ar& ar, Joint& j) {
  ar(j.name, j.parent, j.rest_local, j.inverse_bind);
}
template <class Ar>
void serialize(Ar& ar, Skeleton& s) {
  ar(s.joints);
}
template <class Ar>
void serialize(Ar& ar, Channel& c) {
  ar(c.joint, c.translation_times, c.translations, c.rotation_times, c.rotations, c.scale_times, c.scales);
}
template <class Ar>
void serialize(Ar& ar, MorphChannel& c) {
  ar(c.target, c.times, c.weights);
}
template <class Ar>
void serialize(Ar& ar, Clip& c) {
  ar(c.name, c.duration, c.channels, c.morph_channels);
}
template <class Ar>
void serialize(Ar& ar, Pose& p) {
  ar(p.label, p.joint, p.morph_weights);
}
template <class Ar>
void serialize(Ar& ar, MorphTarget& t) {
  ar(t.name, t.normals);
}
template <class Ar>
void serialize(Ar& ar, Image& i) {
  ar(i.name, i.mime_type, i.data);
}
template <class Ar>
void serialize(Ar& ar, Texture& t) {
  ar(t.gltf, t.sampler, t.images);
}
template <class Ar>
void serialize(Ar& ar, Material& m) {
  ar(m.name, m.base_color, m.base_color_texture, m.gltf, m.textures, m.required_extensions);
}
template <class Ar>
void serialize(Ar& ar, ImportReport& r) {
  ar(r.source_meshes, r.source_vertices, r.welded_vertices, r.faces, r.degenerate_faces_skipped,
     r.nonmanifold_vertices_added, r.unweighted_vertices, r.truncated_vertices, r.renormalized_vertices,
     r.min_weight_sum, r.max_weight_sum, r.zero_area_faces, r.twin_joints, r.morph_targets, r.joints, r.clips, r.rigid,
     r.warnings);
}

namespace {

constexpr uint32_t kMagic = 0x4b534d4f;  // "OMSK"
constexpr uint32_t kVersion = 3;

// The mesh as flat arrays, its connectivity as OpenMesh's own handles: the receiver restores them as they
// are, in linear time (rebuilding with add_face searched every vertex's fan, half of the isolated reader's
// cost), with the same numbering as the sender's. Corners are per halfedge, border halfedges included (zeros).
struct Flat {
  std::vector<double> points;
  std::vector<int32_t> vertex_halfedge;                                // -1: an isolated vertex
  std::vector<int32_t> halfedge_vertex, halfedge_next, halfedge_face;  // face -1: a border halfedge
  std::vector<int32_t> face_halfedge, face_material;
  std::vector<double> corner_normals;           // 3 per halfedge
  std::vector<float> corner_uvs;                // 2 per halfedge
  std::vector<int32_t> set_kinds, set_indices;  // CornerAttributes.hh's sets: CornerKind, set number
  std::vector<std::vector<float>> set_values;   // per set: 4 per halfedge
  std::vector<int32_t> inf_joints;              // Influences::kCapacity per vertex, -1 = none
  std::vector<double> inf_weights;
  std::vector<MorphTarget> morph_targets;
  std::vector<MorphDeltas> morph_deltas;
  Skeleton skeleton;
  std::vector<Pose> poses;
  std::vector<Clip> clips;
  std::vector<Material> materials;

  template <class Ar>
  void serialize(Ar& ar) {
    ar(points, vertex_halfedge, halfedge_vertex, halfedge_next, halfedge_face, face_halfedge, face_material,
       corner_normals, corner_uvs, set_kinds, set_indices, set_values, inf_joints, inf_weights, morph_targets,
       morph_deltas, skeleton, poses, clips, materials);
  }
};

// Writes straight onto the end of a string.
class AppendBuf : public std::streambuf {
public:
  explicit AppendBuf(std::string& s) : s_(s) {}

protected:
  std::streamsize xsputn(const char* p, std::streamsize n) override {
    s_.append(p, size_t(n));
    return n;
  }
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) s_.push_back(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }

private:
  std::string& s_;
};

// Reads bytes where they are.
class ViewBuf : public std::streambuf {
public:
  ViewBuf(const char* data, size_t size) {
    char* p = const_cast<char*>(data);  // the get area is only read
    setg(p, p, p + size);
  }
};

// What the mesh's own code takes for granted of the handles, so that a corrupt archive is refused here and not
// met as a crash or an endless loop later: every handle in range, a halfedge's next leaves the vertex it
// reaches, keeps its face, closes a triangle in three steps and is no other halfedge's next, and each element
// points at one of its own.
void check_connectivity(const Flat& f) {
  const int64_t nv = int64_t(f.vertex_halfedge.size()), nh = int64_t(f.halfedge_vertex.size()),
                nf = int64_t(f.face_halfedge.size());
  const auto in = [](int64_t i, int64_t n) { return i >= 0 && i < n; };
  const auto fail = [] { throw IOError("import archive: inconsistent connectivity"); };
  for (int64_t h = 0; h < nh; ++h)
    if (!in(f.halfedge_vertex[h], nv) || !in(f.halfedge_next[h], nh) ||
        (f.halfedge_face[h] != -1 && !in(f.halfedge_face[h], nf)))
      fail();
  // next must be a permutation (each halfedge some halfedge's next): else a walk around a border may never
  // come back to where it started.
  std::vector<char> reached(size_t(nh), 0);
  for (int64_t h = 0; h < nh; ++h) {
    const int32_t n = f.halfedge_next[h];
    if (reached[n]++) fail();
    // from(next(h)) = to(opposite(next(h))); the opposite of halfedge i is i ^ 1.
    if (f.halfedge_vertex[n ^ 1] != f.halfedge_vertex[h] || f.halfedge_face[n] != f.halfedge_face[h]) fail();
    if (f.halfedge_face[h] != -1 && f.halfedge_next[f.halfedge_next[n]] != h) fail();
  }
  for (int64_t v = 0; v < nv; ++v) {
    const int32_t h = f.vertex_halfedge[v];
    if (h != -1 && (!in(h, nh) || f.halfedge_vertex[h ^ 1] != v)) fail();
  }
  for (int64_t i = 0; i < nf; ++i)
    if (!in(f.face_halfedge[i], nh) || f.halfedge_face[f.face_halfedge[i]] != i) fail();
}

}  // namespace

std::string save_import(const SkinnedMesh& mesh, const ImportReport& report) {
  std::string out;
  append_import(mesh, report, out);
  return out;
}

void append_import(const SkinnedMesh& mesh, const ImportReport& report, std::string& out) {
  Flat f;
  const auto h_inf = influences_handle(mesh);
  const auto h_fmat = face_material_handle(mesh);
  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  const bool morphs = morph_deltas_handle(mesh, h_delta);
  // The handles are sent as they are: an element deleted but not collected would leave a hole in them.
  if (mesh.has_vertex_status() && mesh.has_edge_status() && mesh.has_face_status()) {
    const auto deleted = [&](auto range) {
      return std::any_of(range.begin(), range.end(), [&](auto h) { return mesh.status(h).deleted(); });
    };
    if (deleted(mesh.all_vertices()) || deleted(mesh.all_edges()) || deleted(mesh.all_faces()))
      throw std::logic_error("import archive: the mesh has deleted elements (garbage_collection() first)");
  }
  // Sized up front: grown by doubling, each array is copied and its new pages faulted in again and again.
  const size_t nv = mesh.n_vertices(), nh = mesh.n_halfedges(), nf = mesh.n_faces(), kc = Influences::kCapacity;
  f.points.reserve(3 * nv);
  f.vertex_halfedge.reserve(nv);
  f.inf_joints.reserve(kc * nv);
  f.inf_weights.reserve(kc * nv);
  if (morphs) f.morph_deltas.reserve(nv);
  f.face_material.reserve(nf);
  f.face_halfedge.reserve(nf);
  for (auto* a : {&f.halfedge_vertex, &f.halfedge_next, &f.halfedge_face}) a->reserve(nh);
  f.corner_normals.reserve(3 * nh);
  f.corner_uvs.reserve(2 * nh);
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    f.points.insert(f.points.end(), {p[0], p[1], p[2]});
    f.vertex_halfedge.push_back(mesh.halfedge_handle(vh).idx());
    const Influences& inf = mesh.property(h_inf, vh);
    for (int k = 0; k < Influences::kCapacity; ++k) {
      f.inf_joints.push_back(k < inf.size() ? inf[k].joint : -1);
      f.inf_weights.push_back(k < inf.size() ? inf[k].weight : 0.0);
    }
    if (morphs) f.morph_deltas.push_back(mesh.property(h_delta, vh));
  }
  const std::vector<CornerChannel> sets = corner_channels(mesh);
  for (const CornerChannel& c : sets) {
    f.set_kinds.push_back(static_cast<int32_t>(c.kind));
    f.set_indices.push_back(c.set);
  }
  f.set_values.resize(sets.size());
  for (auto& v : f.set_values) v.reserve(4 * nh);
  for (auto heh : mesh.halfedges()) {
    f.halfedge_vertex.push_back(mesh.to_vertex_handle(heh).idx());
    f.halfedge_next.push_back(mesh.next_halfedge_handle(heh).idx());
    f.halfedge_face.push_back(mesh.face_handle(heh).idx());
    // A border halfedge is no face's corner: what its attributes hold was never set (zeros are sent).
    const bool corner = !mesh.is_boundary(heh);
    const auto n = corner ? mesh.normal(heh) : SkinnedMesh::Normal(0, 0, 0);
    const auto t = corner ? mesh.texcoord2D(heh) : SkinnedMesh::TexCoord2D(0, 0);
    f.corner_normals.insert(f.corner_normals.end(), {n[0], n[1], n[2]});
    f.corner_uvs.insert(f.corner_uvs.end(), {t[0], t[1]});
    for (size_t i = 0; i < sets.size(); ++i) {
      const OpenMesh::Vec4f x = corner ? mesh.property(sets[i].handle, heh) : OpenMesh::Vec4f(0, 0, 0, 0);
      f.set_values[i].insert(f.set_values[i].end(), x.data(), x.data() + 4);
    }
  }
  for (auto fh : mesh.faces()) {
    f.face_material.push_back(mesh.property(h_fmat, fh));
    f.face_halfedge.push_back(mesh.halfedge_handle(fh).idx());
  }
  f.morph_targets = morph_targets(mesh);
  f.skeleton = skeleton(mesh);
  f.poses = example_poses(mesh);
  f.clips = clips(mesh);
  f.materials = materials(mesh);

  out.reserve(out.size() + 8 * (f.points.size() + f.corner_normals.size() + f.inf_weights.size()) +
              4 * (f.vertex_halfedge.size() + 3 * nh + 2 * nf + f.corner_uvs.size() + f.inf_joints.size()) +
              16 * nh * sets.size() + (1 << 16));
  AppendBuf buf(out);
  std::ostream os(&buf);
  cereal::BinaryOutputArchive ar(os);
  ar(kMagic, kVersion, f, const_cast<ImportReport&>(report));
}

void load_import(const std::string& bytes, SkinnedMesh& mesh, ImportReport& report) {
  load_import(bytes.data(), bytes.size(), mesh, report);
}

void load_import(const char* data, size_t size, SkinnedMesh& mesh, ImportReport& report) {
  Flat f;
  try {
    ViewBuf buf(data, size);
    std::istream is(&buf);
    cereal::BinaryInputArchive ar(is);
    uint32_t magic = 0, version = 0;
    ar(magic, version);
    if (magic != kMagic || version != kVersion) throw IOError("import archive: wrong format or version");
    ar(f, report);
  } catch (const cereal::Exception& e) {
    throw IOError(std::string("import archive: truncated or corrupt (") + e.what() + ")");
  }
  const size_t nv = f.points.size() / 3, nh = f.halfedge_vertex.size(), nf = f.face_material.size();
  const size_t kc = Influences::kCapacity;
  if (f.points.size() != 3 * nv || f.vertex_halfedge.size() != nv || nh % 2 != 0 || f.halfedge_next.size() != nh ||
      f.halfedge_face.size() != nh || f.face_halfedge.size() != nf || f.corner_normals.size() != 3 * nh ||
      f.corner_uvs.size() != 2 * nh || f.inf_joints.size() != kc * nv || f.inf_weights.size() != kc * nv ||
      (!f.morph_deltas.empty() && f.morph_deltas.size() != nv) || f.set_indices.size() != f.set_kinds.size() ||
      f.set_values.size() != f.set_kinds.size() ||
      std::any_of(f.set_values.begin(), f.set_values.end(), [nh](const auto& v) { return v.size() != 4 * nh; }))
    throw IOError("import archive: inconsistent array sizes");
  check_connectivity(f);

  mesh = SkinnedMesh();  // a fresh mesh: clear() would keep the properties (skeleton, clips) of an earlier use
  request_skinned_attributes(mesh);
  const auto h_inf = add_skin(mesh);
  const auto h_fmat = face_material_handle(mesh);
  // Every array (and every per-element property) would otherwise grow by doubling and keep up to half its
  // capacity unused for the whole run (measured: 4.7 MB of the CLI's peak on a 240k-triangle mesh). The
  // margins are the vertices and edges later repair may add; faces are only removed.
  mesh.reserve(nv + nv / 32 + 16, nh / 2 + nf / 32 + 16, nf);
  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  if (!f.morph_targets.empty()) h_delta = add_morph_targets(mesh);
  std::vector<CornerChannel> sets;
  for (size_t i = 0; i < f.set_kinds.size(); ++i) {
    const int kind = f.set_kinds[i], set = f.set_indices[i];
    if ((kind != int(CornerKind::TexCoord) && kind != int(CornerKind::Color)) || set < 0 ||
        set >= (kind == int(CornerKind::Color) ? kMaxColorSets : kMaxTexCoordSets))
      throw IOError("import archive: unknown corner attribute set");
    sets.push_back(add_corner_channel(mesh, CornerKind(kind), set));
  }
  for (size_t v = 0; v < nv; ++v) {
    const auto vh = mesh.add_vertex(SkinnedMesh::Point(f.points[3 * v], f.points[3 * v + 1], f.points[3 * v + 2]));
    Influences inf;
    for (size_t k = 0; k < kc && f.inf_joints[kc * v + k] >= 0; ++k)
      inf.push(f.inf_joints[kc * v + k], f.inf_weights[kc * v + k]);
    mesh.property(h_inf, vh) = inf;
    if (!f.morph_targets.empty()) mesh.property(h_delta, vh) = f.morph_deltas.at(v);
  }
  for (size_t v = 0; v < nv; ++v)
    mesh.set_halfedge_handle(SkinnedMesh::VertexHandle(int(v)), SkinnedMesh::HalfedgeHandle(f.vertex_halfedge[v]));
  for (size_t e = 0; e < nh / 2; ++e)  // new_edge(from, to) makes 2e (to `to`) and 2e + 1 (to `from`)
    mesh.new_edge(SkinnedMesh::VertexHandle(f.halfedge_vertex[2 * e + 1]),
                  SkinnedMesh::VertexHandle(f.halfedge_vertex[2 * e]));
  for (size_t i = 0; i < nf; ++i) {
    const auto fh = mesh.new_face();
    mesh.set_halfedge_handle(fh, SkinnedMesh::HalfedgeHandle(f.face_halfedge[i]));
    mesh.property(h_fmat, fh) = f.face_material[i];
  }
  for (size_t i = 0; i < nh; ++i) {
    const SkinnedMesh::HalfedgeHandle heh{int(i)};
    mesh.set_next_halfedge_handle(heh, SkinnedMesh::HalfedgeHandle(f.halfedge_next[i]));
    mesh.set_face_handle(heh, SkinnedMesh::FaceHandle(f.halfedge_face[i]));
    const double* n = &f.corner_normals[3 * i];
    mesh.set_normal(heh, SkinnedMesh::Normal(n[0], n[1], n[2]));
    mesh.set_texcoord2D(heh, SkinnedMesh::TexCoord2D(f.corner_uvs[2 * i], f.corner_uvs[2 * i + 1]));
    for (size_t s = 0; s < sets.size(); ++s)
      mesh.property(sets[s].handle, heh) = OpenMesh::Vec4f(&f.set_values[s][4 * i]);
  }
  mesh.update_face_normals();
  for (auto fh : mesh.faces()) {
    const auto n = mesh.normal(fh);
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]))
      mesh.set_normal(fh, SkinnedMesh::Normal(0, 0, 0));
  }
  if (!f.morph_targets.empty()) morph_targets(mesh) = std::move(f.morph_targets);
  skeleton(mesh) = std::move(f.skeleton);
  example_poses(mesh) = std::move(f.poses);
  clips(mesh) = std::move(f.clips);
  materials(mesh) = std::move(f.materials);
}

}  // namespace OpenMeshSkinned
