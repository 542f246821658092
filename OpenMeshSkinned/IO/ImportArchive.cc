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
#include <istream>
#include <ostream>
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
constexpr uint32_t kVersion = 2;

// The mesh as flat arrays: the face list rebuilds the same connectivity (the importer already split
// every complex edge and vertex), and corners are stored in each face's vertex order.
struct Flat {
  std::vector<double> points;
  std::vector<int32_t> face_vertices, face_material;
  std::vector<double> corner_normals;           // 3 x 3 per face
  std::vector<float> corner_uvs;                // 3 x 2 per face
  std::vector<int32_t> set_kinds, set_indices;  // CornerAttributes.hh's sets: CornerKind, set number
  std::vector<std::vector<float>> set_values;   // per set: 3 x 4 per face
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
    ar(points, face_vertices, face_material, corner_normals, corner_uvs, set_kinds, set_indices, set_values, inf_joints,
       inf_weights, morph_targets, morph_deltas, skeleton, poses, clips, materials);
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
  // Sized up front: grown by doubling, each array is copied and its new pages faulted in again and again.
  const size_t nv = mesh.n_vertices(), nf = mesh.n_faces(), kc = Influences::kCapacity;
  f.points.reserve(3 * nv);
  f.inf_joints.reserve(kc * nv);
  f.inf_weights.reserve(kc * nv);
  if (morphs) f.morph_deltas.reserve(nv);
  f.face_material.reserve(nf);
  f.face_vertices.reserve(3 * nf);
  f.corner_normals.reserve(9 * nf);
  f.corner_uvs.reserve(6 * nf);
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    f.points.insert(f.points.end(), {p[0], p[1], p[2]});
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
  for (auto& v : f.set_values) v.reserve(12 * nf);
  for (auto fh : mesh.faces()) {
    f.face_material.push_back(mesh.property(h_fmat, fh));
    for (auto heh : mesh.fh_range(fh)) {
      f.face_vertices.push_back(mesh.to_vertex_handle(heh).idx());
      const auto& n = mesh.normal(heh);
      const auto& t = mesh.texcoord2D(heh);
      f.corner_normals.insert(f.corner_normals.end(), {n[0], n[1], n[2]});
      f.corner_uvs.insert(f.corner_uvs.end(), {t[0], t[1]});
      for (size_t i = 0; i < sets.size(); ++i) {
        const OpenMesh::Vec4f& x = mesh.property(sets[i].handle, heh);
        f.set_values[i].insert(f.set_values[i].end(), x.data(), x.data() + 4);
      }
    }
  }
  f.morph_targets = morph_targets(mesh);
  f.skeleton = skeleton(mesh);
  f.poses = example_poses(mesh);
  f.clips = clips(mesh);
  f.materials = materials(mesh);

  out.reserve(out.size() + 8 * (f.points.size() + f.corner_normals.size() + f.inf_weights.size()) +
              4 * (f.face_vertices.size() + f.face_material.size() + f.corner_uvs.size() + f.inf_joints.size()) +
              (1 << 16));
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
  const size_t nv = f.points.size() / 3, nf = f.face_material.size();
  const size_t kc = Influences::kCapacity;
  if (f.points.size() != 3 * nv || f.face_vertices.size() != 3 * nf || f.corner_normals.size() != 9 * nf ||
      f.corner_uvs.size() != 6 * nf || f.inf_joints.size() != kc * nv || f.inf_weights.size() != kc * nv ||
      (!f.morph_deltas.empty() && f.morph_deltas.size() != nv) || f.set_indices.size() != f.set_kinds.size() ||
      f.set_values.size() != f.set_kinds.size() ||
      std::any_of(f.set_values.begin(), f.set_values.end(), [nf](const auto& v) { return v.size() != 12 * nf; }))
    throw IOError("import archive: inconsistent array sizes");

  mesh = SkinnedMesh();  // a fresh mesh: clear() would keep the properties (skeleton, clips) of an earlier use
  request_skinned_attributes(mesh);
  const auto h_inf = add_skin(mesh);
  const auto h_fmat = face_material_handle(mesh);
  // Every array (and every per-element property) would otherwise grow by doubling and keep up to half its
  // capacity unused for the whole run (measured: 4.7 MB of the CLI's peak on a 240k-triangle mesh). A closed
  // triangle mesh has 3F/2 edges; the margins cover open borders and the vertices non-manifold repair adds.
  mesh.reserve(nv + nv / 32 + 16, nf + nf / 2 + nf / 32 + 16, nf);
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
  for (size_t i = 0; i < nf; ++i) {
    std::vector<SkinnedMesh::VertexHandle> vs;
    for (int c = 0; c < 3; ++c) {
      const int32_t v = f.face_vertices[3 * i + c];
      if (v < 0 || size_t(v) >= nv) throw IOError("import archive: face index out of range");
      vs.push_back(mesh.vertex_handle(v));
    }
    const auto fh = mesh.add_face(vs);
    if (!fh.is_valid()) throw IOError("import archive: a face cannot be rebuilt");
    mesh.property(h_fmat, fh) = f.face_material[i];
    for (auto heh : mesh.fh_range(fh))
      for (int c = 0; c < 3; ++c) {
        if (vs[c] != mesh.to_vertex_handle(heh)) continue;
        const double* n = &f.corner_normals[9 * i + 3 * c];
        mesh.set_normal(heh, SkinnedMesh::Normal(n[0], n[1], n[2]));
        mesh.set_texcoord2D(heh, SkinnedMesh::TexCoord2D(f.corner_uvs[6 * i + 2 * c], f.corner_uvs[6 * i + 2 * c + 1]));
        for (size_t s = 0; s < sets.size(); ++s)
          mesh.property(sets[s].handle, heh) = OpenMesh::Vec4f(&f.set_values[s][12 * i + 4 * c]);
      }
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
