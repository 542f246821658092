#include "OpenMeshSkinned/IO/Import.hh"

#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Skin/Validate.hh"

#include <OpenMesh/Core/System/omstream.hh>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/LU>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <unordered_map>

namespace OpenMeshSkinned {
namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return e;
}

// Split copies of one vertex carry bit-identical position and skin; hashing the bits welds exactly those
// and never merges two distinct vertices that merely lie close together.
struct WeldKey {
  double p[3];
  Influences inf;
  bool operator==(const WeldKey& o) const {
    return std::memcmp(p, o.p, sizeof p) == 0 && inf == o.inf;
  }
};
struct WeldHash {
  size_t operator()(const WeldKey& k) const {
    size_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, size_t n) {
      const unsigned char* b = static_cast<const unsigned char*>(data);
      for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    mix(k.p, sizeof k.p);
    for (const JointWeight& jw : k.inf) {
      mix(&jw.joint, sizeof jw.joint);
      mix(&jw.weight, sizeof jw.weight);
    }
    return h;
  }
};

struct SceneNodes {
  std::vector<const aiNode*> nodes;   // pre-order: parents first
  std::vector<int> parent;
  std::vector<Eigen::Matrix4d> global;
  std::unordered_map<std::string, int> by_name;
  std::unordered_map<const aiNode*, int> index;

  explicit SceneNodes(const aiNode* root) { visit(root, -1); }
  void visit(const aiNode* n, int p) {
    const int i = static_cast<int>(nodes.size());
    nodes.push_back(n);
    parent.push_back(p);
    global.push_back(p < 0 ? to_eigen(n->mTransformation) : Eigen::Matrix4d(global[p] * to_eigen(n->mTransformation)));
    by_name.emplace(n->mName.C_Str(), i);  // first one wins, as assimp's FindNode does
    index[n] = i;
    for (unsigned c = 0; c < n->mNumChildren; ++c) visit(n->mChildren[c], i);
  }
};

Material read_material(const aiMaterial* m) {
  Material out;
  aiString name;
  if (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
  aiColor4D c;
  if (m->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
    out.base_color[0] = c.r;
    out.base_color[1] = c.g;
    out.base_color[2] = c.b;
    out.base_color[3] = c.a;
  }
  aiString tex;
  if (m->GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == AI_SUCCESS ||
      m->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS) {
    // "*N" names a texture embedded in the source; it has no file to point at.
    if (tex.length > 0 && tex.C_Str()[0] != '*') out.base_color_texture = tex.C_Str();
  }
  return out;
}

// A vertex where several face fans meet (OpenMesh accepts it, but its circulators see one fan only and
// the decimater would treat it as a boundary) gets one copy per extra fan, as OpenMesh's readers do for
// complex edges. Returns the number of copies.
size_t split_nonmanifold_vertices(SkinnedMesh& mesh, OpenMesh::FPropHandleT<int> h_fmat) {
  const auto h_inf = influences_handle(mesh);
  size_t copies = 0;
  std::vector<std::vector<SkinnedMesh::FaceHandle>> faces_of(mesh.n_vertices());
  for (auto fh : mesh.faces())
    for (auto vh : mesh.fv_range(fh)) faces_of[vh.idx()].push_back(fh);
  struct Corner {
    SkinnedMesh::VertexHandle v;
    SkinnedMesh::Normal n;
    SkinnedMesh::TexCoord2D t;
  };
  for (size_t vi = 0; vi < faces_of.size(); ++vi) {
    const SkinnedMesh::VertexHandle vh(static_cast<int>(vi));
    if (mesh.status(vh).deleted() || mesh.is_manifold(vh)) continue;
    // Circulating the outgoing halfedges walks fan after fan; a boundary halfedge (no face) separates two.
    std::vector<SkinnedMesh::HalfedgeHandle> out;
    for (auto heh : mesh.voh_range(vh)) out.push_back(heh);
    const auto first_gap = std::find_if(out.begin(), out.end(), [&](auto h) { return mesh.is_boundary(h); });
    if (first_gap == out.end()) continue;
    std::rotate(out.begin(), first_gap, out.end());
    std::vector<std::vector<SkinnedMesh::FaceHandle>> fans;
    for (auto heh : out) {
      if (mesh.is_boundary(heh)) {
        fans.emplace_back();
        continue;
      }
      fans.back().push_back(mesh.face_handle(heh));
    }
    fans.erase(std::remove_if(fans.begin(), fans.end(), [](const auto& f) { return f.empty(); }), fans.end());
    for (size_t fi = 1; fi < fans.size(); ++fi) {
    const std::vector<SkinnedMesh::FaceHandle>& others = fans[fi];
    const auto copy = mesh.add_vertex(mesh.point(vh));
    mesh.property(h_inf, copy) = mesh.property(h_inf, vh);
    ++copies;
    for (auto fh : others) {
      std::vector<Corner> corners;
      for (auto heh : mesh.fh_range(fh)) {
        const SkinnedMesh::VertexHandle to = mesh.to_vertex_handle(heh);
        corners.push_back({to == vh ? SkinnedMesh::VertexHandle(copy) : to, mesh.normal(heh), mesh.texcoord2D(heh)});
      }
      const int mat = mesh.property(h_fmat, fh);
      mesh.delete_face(fh, false);
      auto nf = mesh.add_face(corners[0].v, corners[1].v, corners[2].v);
      if (!nf.is_valid()) {
        for (Corner& c : corners) {
          const auto own = mesh.add_vertex(mesh.point(c.v));
          mesh.property(h_inf, own) = mesh.property(h_inf, c.v);
          c.v = own;
          ++copies;
        }
        nf = mesh.add_face(corners[0].v, corners[1].v, corners[2].v);
      }
      faces_of.resize(mesh.n_vertices());
      mesh.property(h_fmat, nf) = mat;
      for (auto heh : mesh.fh_range(nf))
        for (const Corner& c : corners)
          if (c.v == mesh.to_vertex_handle(heh)) {
            mesh.set_normal(heh, c.n);
            mesh.set_texcoord2D(heh, c.t);
          }
      for (const Corner& c : corners) faces_of[c.v.idx()].push_back(nf);
    }
    }
  }
  return copies;
}

}  // namespace

ImportReport import_skinned(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  std::error_code ec;
  if (!fs::exists(path, ec)) throw fail("file does not exist");
  if (fs::is_directory(path, ec)) throw fail("is a directory, not a file");
  if (fs::file_size(path, ec) == 0) throw fail("file is empty");

  Assimp::Importer importer;
  // No PreTransformVertices or OptimizeGraph: both would destroy the skeleton we need.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene) {
    std::string msg = importer.GetErrorString();
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    for (char& ch : msg)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw fail("cannot be read: " + msg);
  }
  if (!scene->mRootNode || scene->mNumMeshes == 0) throw fail("contains no mesh");

  const SceneNodes sn(scene->mRootNode);
  ImportReport rep;

  // Mesh instances: (node, mesh index). A mesh used by several nodes is instanced several times.
  struct Instance {
    int node;
    unsigned mesh;
  };
  std::vector<Instance> instances;
  for (size_t i = 0; i < sn.nodes.size(); ++i)
    for (unsigned k = 0; k < sn.nodes[i]->mNumMeshes; ++k) {
      const aiMesh* am = scene->mMeshes[sn.nodes[i]->mMeshes[k]];
      if (am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) instances.push_back({static_cast<int>(i), sn.nodes[i]->mMeshes[k]});
    }
  if (instances.empty()) throw fail("contains no triangle mesh");

  // Which scene nodes become joints: every bone, every node carrying an unskinned mesh, and their ancestors
  // (ancestors move the bones when animated).
  bool any_bones = false;
  std::vector<char> needed(sn.nodes.size(), 0);
  auto need = [&](int n) {
    for (; n >= 0 && !needed[n]; n = sn.parent[n]) needed[n] = 1;
  };
  for (const Instance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    if (am->mNumBones == 0) {
      need(in.node);
      continue;
    }
    any_bones = true;
    need(in.node);  // target for vertices no bone touches
    for (unsigned b = 0; b < am->mNumBones; ++b) {
      auto it = sn.by_name.find(am->mBones[b]->mName.C_Str());
      if (it == sn.by_name.end())
        throw fail(std::string("bone \"") + am->mBones[b]->mName.C_Str() + "\" has no node in the scene");
      need(it->second);
    }
  }
  rep.rigid = !any_bones;
  if (rep.rigid) rep.warnings.push_back("no skin in the file: every mesh is bound rigidly to its node");

  mesh.clear();
  request_skinned_attributes(mesh);
  const auto h_inf = add_skin(mesh);
  const auto h_fmat = face_material_handle(mesh);

  Skeleton& skel = skeleton(mesh);
  std::vector<int> joint_of_node(sn.nodes.size(), -1);
  for (size_t i = 0; i < sn.nodes.size(); ++i) {
    if (!needed[i]) continue;
    Joint j;
    j.name = sn.nodes[i]->mName.C_Str();
    j.parent = sn.parent[i] < 0 ? -1 : joint_of_node[sn.parent[i]];
    j.rest_local = to_eigen(sn.nodes[i]->mTransformation);
    j.inverse_bind = sn.global[i].inverse();
    joint_of_node[i] = skel.size();
    skel.joints.push_back(j);
  }
  // Bones' inverse binds come from the file: the offset matrix maps mesh space to bone space, and our
  // vertices live in root space (mesh space moved by the mesh node's global transform).
  std::vector<char> bind_set(skel.joints.size(), 0);
  for (const Instance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    const Eigen::Matrix4d mesh_to_root_inv = sn.global[in.node].inverse();
    for (unsigned b = 0; b < am->mNumBones; ++b) {
      const int j = joint_of_node[sn.by_name.at(am->mBones[b]->mName.C_Str())];
      if (bind_set[j]) continue;
      skel.joints[j].inverse_bind = to_eigen(am->mBones[b]->mOffsetMatrix) * mesh_to_root_inv;
      bind_set[j] = 1;
    }
  }
  rep.joints = skel.joints.size();

  for (unsigned m = 0; m < scene->mNumMaterials; ++m) materials(mesh).push_back(read_material(scene->mMaterials[m]));

  // OpenMesh prints a line per refused face; we handle and count those ourselves.
  struct QuietOmerr {
    QuietOmerr() { omerr().disable(); }
    ~QuietOmerr() { omerr().enable(); }
  } quiet;
  std::unordered_map<WeldKey, SkinnedMesh::VertexHandle, WeldHash> weld;
  std::vector<SkinnedMesh::VertexHandle> corner_vh;
  for (const Instance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    ++rep.source_meshes;
    rep.source_vertices += am->mNumVertices;
    const Eigen::Matrix4d g = sn.global[in.node];
    const Eigen::Matrix3d normal_matrix = g.topLeftCorner<3, 3>().inverse().transpose();
    const int node_joint = joint_of_node[in.node];

    std::vector<Influences> inf(am->mNumVertices);
    std::vector<char> touched(am->mNumVertices, 0);
    std::vector<size_t> over_capacity;
    for (unsigned b = 0; b < am->mNumBones; ++b) {
      const aiBone* bone = am->mBones[b];
      const int j = joint_of_node[sn.by_name.at(bone->mName.C_Str())];
      for (unsigned w = 0; w < bone->mNumWeights; ++w) {
        const aiVertexWeight& vw = bone->mWeights[w];
        if (vw.mVertexId >= am->mNumVertices)
          throw fail("bone \"" + std::string(bone->mName.C_Str()) + "\" weights vertex " + std::to_string(vw.mVertexId) +
                     " of a mesh with " + std::to_string(am->mNumVertices) + " vertices");
        const double wt = vw.mWeight;
        if (!std::isfinite(wt))
          throw fail("vertex " + std::to_string(vw.mVertexId) + " has a non-finite weight for bone \"" + bone->mName.C_Str() + "\"");
        if (wt < 0.0)
          throw fail("vertex " + std::to_string(vw.mVertexId) + " has negative weight " + std::to_string(wt) + " for bone \"" +
                     bone->mName.C_Str() + "\"");
        touched[vw.mVertexId] = 1;
        if (wt == 0.0) continue;
        Influences& vi = inf[vw.mVertexId];
        if (!vi.add(j, wt)) {
          // Full: keep the heaviest, so the capacity drops the least weight.
          vi.sort();
          if (wt > vi[Influences::kCapacity - 1].weight) {
            Influences tmp;
            for (int k = 0; k < Influences::kCapacity - 1; ++k) tmp.push(vi[k].joint, vi[k].weight);
            tmp.push(j, wt);
            vi = tmp;
          }
          over_capacity.push_back(vw.mVertexId);
        }
      }
    }
    std::sort(over_capacity.begin(), over_capacity.end());
    rep.truncated_vertices += std::unique(over_capacity.begin(), over_capacity.end()) - over_capacity.begin();

    std::vector<SkinnedMesh::VertexHandle> vmap(am->mNumVertices);
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      Influences& vi = inf[v];
      if (am->mNumBones == 0 || !touched[v]) {
        if (am->mNumBones > 0) ++rep.unweighted_vertices;
        vi = Influences::rigid(node_joint);
      } else {
        const double s = vi.sum();
        if (s <= 0.0) throw fail("vertex " + std::to_string(v) + " has bone weights that sum to 0");
        rep.min_weight_sum = std::min(rep.min_weight_sum, s);
        rep.max_weight_sum = std::max(rep.max_weight_sum, s);
        if (!opt.normalize_weights && std::abs(s - 1.0) > opt.sum_tolerance &&
            !std::binary_search(over_capacity.begin(), over_capacity.end(), v)) {
          throw fail("vertex " + std::to_string(v) + " has bone weights that sum to " + std::to_string(s) +
                     ", not 1 (tolerance " + std::to_string(opt.sum_tolerance) + ")");
        }
        if (std::abs(s - 1.0) > 1e-4) ++rep.renormalized_vertices;  // float files round at ~1e-7
        vi.normalize();
        vi.sort();
      }
      const aiVector3D& p = am->mVertices[v];
      const Eigen::Vector3d q = (g * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
      WeldKey key{{q.x(), q.y(), q.z()}, vi};
      auto it = weld.find(key);
      if (it == weld.end()) {
        const auto vh = mesh.add_vertex(SkinnedMesh::Point(q.x(), q.y(), q.z()));
        mesh.property(h_inf, vh) = vi;
        it = weld.emplace(key, vh).first;
      }
      vmap[v] = it->second;
    }

    const bool has_uv = am->HasTextureCoords(0);
    const bool has_n = am->HasNormals();
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& af = am->mFaces[f];
      if (af.mNumIndices != 3) continue;  // points and lines left over by SortByPType
      corner_vh = {vmap[af.mIndices[0]], vmap[af.mIndices[1]], vmap[af.mIndices[2]]};
      if (corner_vh[0] == corner_vh[1] || corner_vh[1] == corner_vh[2] || corner_vh[0] == corner_vh[2]) {
        ++rep.degenerate_faces_skipped;
        continue;
      }
      auto fh = mesh.add_face(corner_vh);
      if (!fh.is_valid()) {
        // A complex edge (more than two faces) or vertex: OpenMesh cannot hold it. Like OpenMesh's own
        // readers, give this face private copies of its vertices so that no face is dropped.
        for (auto& vh : corner_vh) {
          const auto copy = mesh.add_vertex(mesh.point(vh));
          mesh.property(h_inf, copy) = mesh.property(h_inf, vh);
          vh = copy;
        }
        rep.nonmanifold_vertices_added += 3;
        fh = mesh.add_face(corner_vh);
        if (!fh.is_valid()) throw fail("face " + std::to_string(f) + " cannot be added even with copied vertices");
      }
      mesh.property(h_fmat, fh) = static_cast<int>(am->mMaterialIndex);
      for (auto heh : mesh.fh_range(fh)) {
        const auto to = mesh.to_vertex_handle(heh);
        for (int c = 0; c < 3; ++c) {
          if (corner_vh[c] != to) continue;
          const unsigned src = af.mIndices[c];
          if (has_n) {
            const aiVector3D& n = am->mNormals[src];
            Eigen::Vector3d en = normal_matrix * Eigen::Vector3d(n.x, n.y, n.z);
            if (en.norm() > 0.0) en.normalize();
            mesh.set_normal(heh, SkinnedMesh::Normal(en.x(), en.y(), en.z()));
          }
          if (has_uv) {
            const aiVector3D& t = am->mTextureCoords[0][src];
            mesh.set_texcoord2D(heh, SkinnedMesh::TexCoord2D(t.x, t.y));
          }
        }
      }
      ++rep.faces;
    }
  }
  if (rep.faces == 0) throw fail("contains no usable triangle");
  if (rep.unweighted_vertices > 0)
    rep.warnings.push_back(std::to_string(rep.unweighted_vertices) +
                           " vertices had no bone weight: bound rigidly to their mesh's node");
  if (rep.truncated_vertices > 0)
    rep.warnings.push_back(std::to_string(rep.truncated_vertices) + " vertices had more than " +
                           std::to_string(Influences::kCapacity) + " bones: kept the heaviest and renormalised");
  if (rep.renormalized_vertices > 0) {
    std::ostringstream os;
    os << rep.renormalized_vertices << " vertices' weights did not sum to 1 (sums " << rep.min_weight_sum << " to "
       << rep.max_weight_sum << "): rescaled to 1";
    rep.warnings.push_back(os.str());
  }
  if (rep.degenerate_faces_skipped > 0)
    rep.warnings.push_back(std::to_string(rep.degenerate_faces_skipped) + " degenerate triangles skipped");

  rep.nonmanifold_vertices_added += split_nonmanifold_vertices(mesh, h_fmat);
  if (rep.nonmanifold_vertices_added > 0)
    rep.warnings.push_back("non-manifold input: " + std::to_string(rep.nonmanifold_vertices_added) +
                           " vertices duplicated so that faces on complex edges and vertices are kept");

  // Vertices that no face uses (e.g. of skipped faces) would only confuse the decimater.
  for (auto vh : mesh.vertices())
    if (mesh.is_isolated(vh)) mesh.delete_vertex(vh, false);
  mesh.garbage_collection();
  rep.welded_vertices = mesh.n_vertices();
  mesh.update_face_normals();

  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    const aiAnimation* an = scene->mAnimations[a];
    const double tps = an->mTicksPerSecond > 0.0 ? an->mTicksPerSecond : 25.0;
    Clip clip;
    clip.name = an->mName.length > 0 ? an->mName.C_Str() : "clip" + std::to_string(a);
    clip.duration = an->mDuration / tps;
    for (unsigned c = 0; c < an->mNumChannels; ++c) {
      const aiNodeAnim* na = an->mChannels[c];
      auto it = sn.by_name.find(na->mNodeName.C_Str());
      if (it == sn.by_name.end() || joint_of_node[it->second] < 0) continue;  // moves nothing we keep
      Channel ch;
      ch.joint = joint_of_node[it->second];
      for (unsigned k = 0; k < na->mNumPositionKeys; ++k) {
        const auto& key = na->mPositionKeys[k];
        ch.translation_times.push_back(key.mTime / tps);
        ch.translations.emplace_back(key.mValue.x, key.mValue.y, key.mValue.z);
      }
      for (unsigned k = 0; k < na->mNumRotationKeys; ++k) {
        const auto& key = na->mRotationKeys[k];
        ch.rotation_times.push_back(key.mTime / tps);
        ch.rotations.emplace_back(key.mValue.w, key.mValue.x, key.mValue.y, key.mValue.z);
      }
      for (unsigned k = 0; k < na->mNumScalingKeys; ++k) {
        const auto& key = na->mScalingKeys[k];
        ch.scale_times.push_back(key.mTime / tps);
        ch.scales.emplace_back(key.mValue.x, key.mValue.y, key.mValue.z);
      }
      for (double t : ch.translation_times) clip.duration = std::max(clip.duration, t);
      for (double t : ch.rotation_times) clip.duration = std::max(clip.duration, t);
      for (double t : ch.scale_times) clip.duration = std::max(clip.duration, t);
      clip.channels.push_back(std::move(ch));
    }
    clips(mesh).push_back(std::move(clip));
  }
  rep.clips = clips(mesh).size();
  example_poses(mesh) = {Pose::identity(skel.size())};

  try {
    ValidationOptions vo;
    vo.sum_tolerance = opt.sum_tolerance;
    validate_skin(mesh, vo);
  } catch (const SkinError& e) {
    throw fail(e.what());
  }
  return rep;
}

}  // namespace OpenMeshSkinned
