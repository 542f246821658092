#include "OpenMeshSkinned/IO/ImportGeometry.hh"

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/Mesh/NonManifold.hh"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace OpenMeshSkinned::detail {

namespace {

// Split copies of one vertex carry bit-identical position and skin; hashing the bits welds exactly those
// and never merges two distinct vertices that merely lie close together.
struct WeldKey {
  double p[3];
  Influences inf;
  MorphDeltas deltas;
  bool operator==(const WeldKey& o) const {
    return std::memcmp(p, o.p, sizeof p) == 0 && inf == o.inf && deltas == o.deltas;
  }
};
struct WeldHash {
  // Word by word (a byte-wise FNV over the ~120 bytes of a key was a tenth of the weld's time); the same
  // bits as WeldKey's equality compares, so equal keys hash alike.
  size_t operator()(const WeldKey& k) const {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    auto mix = [&h](uint64_t v) {
      h = (h ^ v) * 0xff51afd7ed558ccdull;
      h ^= h >> 29;
    };
    for (double c : k.p) mix(bits(c));
    for (const JointWeight& jw : k.inf) {
      mix(uint64_t(uint32_t(jw.joint)));
      mix(bits(jw.weight));
    }
    for (const Eigen::Vector3f& d : k.deltas)
      for (int c = 0; c < 3; ++c) {
        uint32_t b;
        std::memcpy(&b, &d[c], sizeof b);
        mix(b);
      }
    return size_t(h);
  }
  static uint64_t bits(double x) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  }
};

}  // namespace

struct GeometryBuilder::Weld {
  std::unordered_map<WeldKey, SkinnedMesh::VertexHandle, WeldHash> map;
};

GeometryBuilder::GeometryBuilder(SkinnedMesh& mesh, size_t n_targets, const ImportOptions& opt, ImportReport& rep,
                                 const std::string& path)
    : mesh_(mesh), n_targets_(n_targets), opt_(opt), rep_(rep), path_(path), weld_(std::make_unique<Weld>()) {
  h_inf_ = influences_handle(mesh);
  h_fmat_ = face_material_handle(mesh);
  if (n_targets > 0) morph_deltas_handle(mesh, h_delta_);
}

GeometryBuilder::~GeometryBuilder() = default;

void GeometryBuilder::reserve(size_t vertices) { weld_->map.reserve(vertices); }

// The mesh's bind space: where a viewer shows it in the rest pose. Unskinned, that is its node's world
// matrix; skinned, the glTF rule gives sum_k w_k J_k O_k v, and for a well-formed skin every bone gives
// the same J_k O_k. Files whose rest pose is not their bind pose for some bones (FBX) give several: take
// the one that carries the most skin weight, which is also the one a round trip through our own export
// maps to identity. Vertices are stored there and each bone's inverse bind becomes O_k B^-1, so posing
// J_k(t) O_k B^-1 (B v) is exact whichever was chosen.
Eigen::Matrix4d GeometryBuilder::bind_space(const aiMesh* am, const SceneNodes& sn, const JointMap& joints,
                                            int node) const {
  Eigen::Matrix4d B = sn.global[node];
  std::vector<std::pair<Eigen::Matrix4d, double>> spaces;  // candidate, weight agreeing with it
  for (unsigned b = 0; b < am->mNumBones; ++b) {
    const aiBone* bone = am->mBones[b];
    const Eigen::Matrix4d c = sn.global[joints.bone_node(bone)] * to_matrix(bone->mOffsetMatrix);
    double total = 0.0;
    for (unsigned w = 0; w < bone->mNumWeights; ++w) total += bone->mWeights[w].mWeight;
    const double tol = 1e-4 * std::max(1.0, c.cwiseAbs().maxCoeff());
    auto same = std::find_if(spaces.begin(), spaces.end(),
                             [&](const auto& s) { return (s.first - c).cwiseAbs().maxCoeff() <= tol; });
    if (same == spaces.end())
      spaces.emplace_back(c, total);
    else
      same->second += total;
  }
  const auto best =
      std::max_element(spaces.begin(), spaces.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
  if (best != spaces.end()) B = best->first;
  if (!B.allFinite() || std::abs(B.topLeftCorner<3, 3>().determinant()) < 1e-300)
    throw IOError(path_ + ": mesh \"" + am->mName.C_Str() + "\" has a singular or non-finite bind transform");
  return B;
}

// Each vertex's influences as the file gives them, checked, summed to one; unweighted vertices of a
// skinned mesh (and every vertex of an unskinned one) follow the mesh's node.
std::vector<Influences> GeometryBuilder::read_weights(const aiMesh* am, JointMap& joints, const Eigen::Matrix4d& B_inv,
                                                      int node_joint) {
  auto fail = [this](const std::string& what) { return IOError(path_ + ": " + what); };
  std::vector<Influences> inf(am->mNumVertices);
  std::vector<char> touched(am->mNumVertices, 0);
  std::vector<size_t> over_capacity;
  for (unsigned b = 0; b < am->mNumBones; ++b) {
    const aiBone* bone = am->mBones[b];
    const int j = joints.joint_for(joints.bone_node(bone), to_matrix(bone->mOffsetMatrix) * B_inv);
    for (unsigned w = 0; w < bone->mNumWeights; ++w) {
      const aiVertexWeight& vw = bone->mWeights[w];
      if (vw.mVertexId >= am->mNumVertices)
        throw fail("bone \"" + std::string(bone->mName.C_Str()) + "\" weights vertex " + std::to_string(vw.mVertexId) +
                   " of a mesh with " + std::to_string(am->mNumVertices) + " vertices");
      const double wt = vw.mWeight;
      if (!std::isfinite(wt))
        throw fail("vertex " + std::to_string(vw.mVertexId) + " has a non-finite weight for bone \"" +
                   bone->mName.C_Str() + "\"");
      if (wt < 0.0)
        throw fail("vertex " + std::to_string(vw.mVertexId) + " has negative weight " + std::to_string(wt) +
                   " for bone \"" + bone->mName.C_Str() + "\"");
      touched[vw.mVertexId] = 1;
      if (wt == 0.0) continue;
      if (!inf[vw.mVertexId].add_keeping_heaviest(j, wt)) over_capacity.push_back(vw.mVertexId);
    }
  }
  std::sort(over_capacity.begin(), over_capacity.end());
  rep_.truncated_vertices += std::unique(over_capacity.begin(), over_capacity.end()) - over_capacity.begin();

  for (unsigned v = 0; v < am->mNumVertices; ++v) {
    Influences& vi = inf[v];
    if (am->mNumBones == 0 || !touched[v]) {
      if (am->mNumBones > 0) ++rep_.unweighted_vertices;
      vi = Influences::rigid(node_joint);
      continue;
    }
    const double s = vi.sum();
    if (s <= 0.0) throw fail("vertex " + std::to_string(v) + " has bone weights that sum to 0");
    rep_.min_weight_sum = std::min(rep_.min_weight_sum, s);
    rep_.max_weight_sum = std::max(rep_.max_weight_sum, s);
    if (!opt_.normalize_weights && std::abs(s - 1.0) > opt_.sum_tolerance &&
        !std::binary_search(over_capacity.begin(), over_capacity.end(), v)) {
      throw fail("vertex " + std::to_string(v) + " has bone weights that sum to " + std::to_string(s) +
                 ", not 1 (tolerance " + std::to_string(opt_.sum_tolerance) + ")");
    }
    if (std::abs(s - 1.0) > 1e-4) ++rep_.renormalized_vertices;  // float files round at ~1e-7
    vi.normalize();
    vi.sort();
  }
  return inf;
}

void GeometryBuilder::add(const aiScene* scene, const SceneNodes& sn, JointMap& joints, const MeshInstance& in,
                          size_t target_base) {
  const aiMesh* am = scene->mMeshes[in.mesh];
  ++rep_.source_meshes;
  rep_.source_vertices += am->mNumVertices;
  const Eigen::Matrix4d B = bind_space(am, sn, joints, in.node);
  const Eigen::Matrix3d normal_matrix = B.topLeftCorner<3, 3>().inverse().transpose();
  // The node is a joint only where the mesh needs it (JointMap): without a skin, or for unweighted vertices.
  const int node_joint =
      joints.joints_of_node(in.node).empty() ? -1 : joints.joint_for(in.node, sn.global[in.node].inverse());
  const std::vector<Influences> inf = read_weights(am, joints, B.inverse(), node_joint);

  for (unsigned t = 0; t < am->mNumAnimMeshes && n_targets_ > 0; ++t)
    if (am->mAnimMeshes[t]->mNormals) morph_targets(mesh_)[target_base + t].normals = true;

  std::vector<SkinnedMesh::VertexHandle> vmap(am->mNumVertices);
  for (unsigned v = 0; v < am->mNumVertices; ++v) {
    const aiVector3D& p = am->mVertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw IOError(path_ + ": vertex " + std::to_string(v) + " of mesh \"" + am->mName.C_Str() +
                    "\" has a non-finite position");
    const Eigen::Vector3d q = (B * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
    WeldKey key{{q.x(), q.y(), q.z()}, inf[v], {}};
    if (n_targets_ > 0) {
      key.deltas.assign(n_targets_, Eigen::Vector3f::Zero());
      for (unsigned t = 0; t < am->mNumAnimMeshes; ++t) {
        const aiAnimMesh* an = am->mAnimMeshes[t];
        if (!an->mVertices) continue;               // a target of normals only: no offset
        const aiVector3D d = an->mVertices[v] - p;  // assimp stores the target's positions, not offsets
        const Eigen::Vector3d bd = B.topLeftCorner<3, 3>() * Eigen::Vector3d(d.x, d.y, d.z);
        if (!bd.allFinite())
          throw IOError(path_ + ": morph target " + std::to_string(t) + " has a non-finite position at vertex " +
                        std::to_string(v));
        key.deltas[target_base + t] = bd.cast<float>();
      }
    }
    auto it = weld_->map.find(key);
    if (it == weld_->map.end()) {
      const auto vh = mesh_.add_vertex(SkinnedMesh::Point(q.x(), q.y(), q.z()));
      mesh_.property(h_inf_, vh) = inf[v];
      if (n_targets_ > 0) mesh_.property(h_delta_, vh) = key.deltas;
      it = weld_->map.emplace(std::move(key), vh).first;
    }
    vmap[v] = it->second;
  }
  add_faces(am, vmap, normal_matrix);
  note_dropped(am);
}

void GeometryBuilder::warn(int& slot, const std::string& text) {
  if (slot < 0) {
    slot = static_cast<int>(rep_.warnings.size());
    rep_.warnings.push_back(text);
  } else {
    rep_.warnings[slot] = text;
  }
}

// What the mesh has that the output does not carry.
void GeometryBuilder::note_dropped(const aiMesh* am) {
  bool target_tangents = false, target_attributes = false;
  for (unsigned t = 0; t < am->mNumAnimMeshes; ++t) {
    const aiAnimMesh* an = am->mAnimMeshes[t];
    target_tangents |= an->mTangents != nullptr;
    // Some readers copy the base mesh's colours and UVs into every target: only a difference is an offset.
    for (unsigned n = 0; n < AI_MAX_NUMBER_OF_COLOR_SETS; ++n)
      if (an->mColors[n] && am->mColors[n])
        for (unsigned v = 0; v < am->mNumVertices && !target_attributes; ++v)
          target_attributes = !(an->mColors[n][v] == am->mColors[n][v]);
    for (unsigned n = 0; n < AI_MAX_NUMBER_OF_TEXTURECOORDS; ++n)
      if (an->mTextureCoords[n] && am->mTextureCoords[n])
        for (unsigned v = 0; v < am->mNumVertices && !target_attributes; ++v)
          target_attributes = !(an->mTextureCoords[n][v] == am->mTextureCoords[n][v]);
  }
  if (am->HasTangentsAndBitangents() || target_tangents)
    warn(tangent_warning_,
         "the input's tangents (TANGENT, and morph targets' tangent offsets) are not kept: the LODs get tangents "
         "made from their own normals and UVs where a material needs them (a normal map), morph targets none");
  if (target_attributes)
    warn(target_warning_, "morph targets' colour and UV offsets are not kept (position and normal offsets are)");
  // Readers report a third component for some 2D sets (Collada): only a non-zero w is lost.
  bool uvw = false;
  for (unsigned n = 0; n < AI_MAX_NUMBER_OF_TEXTURECOORDS; ++n)
    if (am->HasTextureCoords(n) && am->mNumUVComponents[n] > 2)
      for (unsigned v = 0; v < am->mNumVertices && !uvw; ++v) uvw = am->mTextureCoords[n][v].z != 0.0f;
  if (uvw) warn(uvw_warning_, "3D texture coordinates: only u and v are kept (glTF has 2D UV sets)");
  if (clamped_colours_ > 0)
    warn(clamp_warning_,
         std::to_string(clamped_colours_) + " vertex colour components outside [0, 1] (or not finite) clamped");
}

OpenMesh::Vec4f GeometryBuilder::corner_value(const aiMesh* am, const CornerChannel& ch, unsigned src) {
  OpenMesh::Vec4f x = ch.fallback();
  if (ch.kind == CornerKind::TexCoord) {
    if (!am->HasTextureCoords(ch.set)) return x;
    const aiVector3D& t = am->mTextureCoords[ch.set][src];
    if (std::isfinite(t.x) && std::isfinite(t.y)) x = OpenMesh::Vec4f(t.x, t.y, 0, 0);
    return x;
  }
  if (!am->HasVertexColors(ch.set)) return x;
  const aiColor4D& c = am->mColors[ch.set][src];
  const float in[4] = {c.r, c.g, c.b, c.a};
  for (int k = 0; k < 4; ++k) {
    // glTF colours are in [0, 1]; a non-finite component keeps white's.
    if (!std::isfinite(in[k])) {
      ++clamped_colours_;
      continue;
    }
    x[k] = std::clamp(in[k], 0.0f, 1.0f);
    clamped_colours_ += x[k] != in[k];
  }
  return x;
}

void GeometryBuilder::add_faces(const aiMesh* am, const std::vector<SkinnedMesh::VertexHandle>& vmap,
                                const Eigen::Matrix3d& normal_matrix) {
  const bool has_uv = am->HasTextureCoords(0);
  const bool has_n = am->HasNormals();
  // Every set this mesh has is added to the whole mesh; corners of meshes without it get its fallback.
  for (unsigned n = 1; n < AI_MAX_NUMBER_OF_TEXTURECOORDS && int(n) < kMaxTexCoordSets; ++n)
    if (am->HasTextureCoords(n)) add_corner_channel(mesh_, CornerKind::TexCoord, int(n));
  for (unsigned n = 0; n < AI_MAX_NUMBER_OF_COLOR_SETS && int(n) < kMaxColorSets; ++n)
    if (am->HasVertexColors(n)) add_corner_channel(mesh_, CornerKind::Color, int(n));
  const std::vector<CornerChannel> channels = corner_channels(mesh_);
  std::vector<SkinnedMesh::VertexHandle> corner_vh;
  for (unsigned f = 0; f < am->mNumFaces; ++f) {
    const aiFace& af = am->mFaces[f];
    if (af.mNumIndices != 3) continue;  // points and lines left over by SortByPType
    corner_vh = {vmap[af.mIndices[0]], vmap[af.mIndices[1]], vmap[af.mIndices[2]]};
    if (corner_vh[0] == corner_vh[1] || corner_vh[1] == corner_vh[2] || corner_vh[0] == corner_vh[2]) {
      ++rep_.degenerate_faces_skipped;
      continue;
    }
    auto fh = mesh_.add_face(corner_vh);
    if (!fh.is_valid()) {
      // A complex edge (more than two faces) or vertex: OpenMesh cannot hold it. Like OpenMesh's own
      // readers, give this face private copies of its vertices so that no face is dropped.
      for (auto& vh : corner_vh) vh = copy_vertex(mesh_, vh);
      rep_.nonmanifold_vertices_added += 3;
      fh = mesh_.add_face(corner_vh);
      if (!fh.is_valid())
        throw IOError(path_ + ": face " + std::to_string(f) + " cannot be added even with copied vertices");
    }
    mesh_.property(h_fmat_, fh) = static_cast<int>(am->mMaterialIndex);
    for (auto heh : mesh_.fh_range(fh)) {
      const auto to = mesh_.to_vertex_handle(heh);
      for (int c = 0; c < 3; ++c) {
        if (corner_vh[c] != to) continue;
        const unsigned src = af.mIndices[c];
        // OpenMesh leaves attributes uninitialised: a mesh without normals or UVs gets zeros (a zero
        // normal is recomputed from the faces on export; all-zero UVs are not written).
        Eigen::Vector3d en = Eigen::Vector3d::Zero();
        if (has_n) {
          const aiVector3D& n = am->mNormals[src];
          en = normal_matrix * Eigen::Vector3d(n.x, n.y, n.z);
          if (!en.allFinite() || en.norm() == 0.0)
            en.setZero();
          else
            en.normalize();
        }
        mesh_.set_normal(heh, SkinnedMesh::Normal(en.x(), en.y(), en.z()));
        SkinnedMesh::TexCoord2D uv(0, 0);
        if (has_uv) {
          const aiVector3D& t = am->mTextureCoords[0][src];
          if (std::isfinite(t.x) && std::isfinite(t.y)) uv = SkinnedMesh::TexCoord2D(t.x, t.y);
        }
        mesh_.set_texcoord2D(heh, uv);
        for (const CornerChannel& ch : channels) mesh_.property(ch.handle, heh) = corner_value(am, ch, src);
      }
    }
    ++rep_.faces;
  }
}

}  // namespace OpenMeshSkinned::detail
