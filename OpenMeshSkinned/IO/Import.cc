#include "OpenMeshSkinned/IO/Import.hh"

#include "OpenMeshSkinned/IO/GltfRepair.hh"
#include "OpenMeshSkinned/IO/GltfValueCheck.hh"
#include "OpenMeshSkinned/IO/ImportMaterial.hh"
#include "OpenMeshSkinned/IO/IsolatedImport.hh"
#include "OpenMeshSkinned/IO/ReaderLog.hh"
#include "OpenMeshSkinned/Mesh/NonManifold.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"

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

Eigen::Matrix4d to_matrix(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return e;
}

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
    for (const Eigen::Vector3f& d : k.deltas) mix(d.data(), sizeof(float) * 3);
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
    global.push_back(p < 0 ? to_matrix(n->mTransformation) : Eigen::Matrix4d(global[p] * to_matrix(n->mTransformation)));
    by_name.emplace(n->mName.C_Str(), i);  // first one wins, as assimp's FindNode does
    index[n] = i;
    for (unsigned c = 0; c < n->mNumChildren; ++c) visit(n->mChildren[c], i);
  }
};

}  // namespace

ImportReport import_skinned(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  std::error_code ec;
  if (!fs::exists(path, ec)) throw fail("file does not exist");
  if (fs::is_directory(path, ec)) throw fail("is a directory, not a file");
  if (fs::file_size(path, ec) == 0) throw fail("file is empty");
  const RepairedGltf repaired(path);
  const std::string& read_path = repaired.path().empty() ? path : repaired.path();
  if (opt.isolate) return import_isolated(path, read_path, mesh, opt);
  return detail::import_scene(path, read_path, mesh, opt);
}

ImportReport detail::import_scene(const std::string& path, const std::string& read_path, SkinnedMesh& mesh,
                                  const ImportOptions& opt) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  check_gltf_weights(read_path, path);
  const ReaderLog log;
  Assimp::Importer importer;
  // No PreTransformVertices or OptimizeGraph: both would destroy the skeleton we need.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(read_path, flags);
  if (!scene) {
    std::string msg = importer.GetErrorString();
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    // One line, of a readable length: a reader may quote half the file back.
    for (char& ch : msg)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = ' ';
    if (msg.size() > 240) msg = msg.substr(0, 240) + " [...]";
    throw fail("cannot be read: " + msg);
  }
  if (!scene->mRootNode || scene->mNumMeshes == 0) throw fail("contains no mesh");
  // Skeleton-only files (BVH, MD5 anim) get a stand-in mesh of boxes around the bones from assimp.
  bool stand_in = scene->mNumMaterials > 0;
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    aiString name;
    stand_in &= scene->mMaterials[m]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::string(name.C_Str()) == "SkeletonMaterial";
  }
  if (stand_in) throw fail("contains no mesh, only a skeleton and its animation (nothing to decimate)");

  const SceneNodes sn(scene->mRootNode);
  const std::string source_dir = fs::absolute(fs::path(path)).parent_path().string();
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
  // (ancestors move the bones when animated, and a rotated, scaled scene root is part of every pose).
  bool any_bones = false;
  std::vector<char> needed(sn.nodes.size(), 0);
  auto need = [&](int n) {
    for (; n >= 0 && !needed[n]; n = sn.parent[n]) needed[n] = 1;
  };
  auto bone_node = [&](const aiBone* b) {
    auto it = sn.by_name.find(b->mName.C_Str());
    if (it == sn.by_name.end()) throw fail(std::string("bone \"") + b->mName.C_Str() + "\" has no node in the scene");
    return it->second;
  };
  for (const Instance& in : instances) {
    const aiMesh* am = scene->mMeshes[in.mesh];
    need(in.node);  // an unskinned mesh moves with it; a skinned one binds unweighted vertices to it
    any_bones |= am->mNumBones > 0;
    for (unsigned b = 0; b < am->mNumBones; ++b) need(bone_node(am->mBones[b]));
  }
  rep.rigid = !any_bones;
  if (rep.rigid) rep.warnings.push_back("no skin in the file: every mesh is bound rigidly to its node");

  mesh.clear();
  request_skinned_attributes(mesh);
  const auto h_inf = add_skin(mesh);
  const auto h_fmat = face_material_handle(mesh);

  // One joint per needed node, bound where the node rests (inverse bind = its rest world matrix inverted).
  // A skin whose inverse bind for a node differs from the one already in use (several skins bound in
  // different poses or spaces) gets a twin joint: same parent, same transform, same animation, own bind.
  Skeleton& skel = skeleton(mesh);
  std::vector<std::vector<int>> joints_of_node(sn.nodes.size());
  std::vector<char> claimed;
  for (size_t i = 0; i < sn.nodes.size(); ++i) {
    if (!needed[i]) continue;
    Joint j;
    j.name = sn.nodes[i]->mName.C_Str();
    j.parent = sn.parent[i] < 0 ? -1 : joints_of_node[sn.parent[i]].front();
    j.rest_local = to_matrix(sn.nodes[i]->mTransformation);
    j.inverse_bind = sn.global[i].inverse();
    joints_of_node[i].push_back(skel.size());
    skel.joints.push_back(j);
    claimed.push_back(0);
  }
  auto joint_for = [&](int node, const Eigen::Matrix4d& ib) {
    const double tol = 1e-5 * std::max(1.0, ib.cwiseAbs().maxCoeff());
    for (int j : joints_of_node[node])
      if ((skel.joints[j].inverse_bind - ib).cwiseAbs().maxCoeff() <= tol) return claimed[j] = 1, j;
    const int first = joints_of_node[node].front();
    if (!claimed[first]) {
      skel.joints[first].inverse_bind = ib;
      claimed[first] = 1;
      return first;
    }
    Joint twin = skel.joints[first];
    twin.inverse_bind = ib;
    joints_of_node[node].push_back(skel.size());
    skel.joints.push_back(twin);
    claimed.push_back(1);
    ++rep.twin_joints;
    return skel.size() - 1;
  };

  for (unsigned m = 0; m < scene->mNumMaterials; ++m)
    materials(mesh).push_back(read_material(scene, scene->mMaterials[m], source_dir, rep.warnings));

  // Morph targets of every mesh instance, numbered one after the other.
  std::vector<size_t> target_base(instances.size(), 0);
  size_t n_targets = 0;
  for (size_t ii = 0; ii < instances.size(); ++ii) {
    const aiMesh* am = scene->mMeshes[instances[ii].mesh];
    target_base[ii] = n_targets;
    for (unsigned t = 0; t < am->mNumAnimMeshes; ++t) {
      const aiAnimMesh* an = am->mAnimMeshes[t];
      if (an->mNumVertices != am->mNumVertices)
        throw fail("morph target " + std::to_string(t) + " of mesh \"" + am->mName.C_Str() + "\" has " +
                   std::to_string(an->mNumVertices) + " vertices, the mesh " + std::to_string(am->mNumVertices));
      MorphTarget mt;
      mt.name = an->mName.length ? an->mName.C_Str() : std::string(am->mName.C_Str()) + "_target" + std::to_string(t);
      morph_targets(mesh).push_back(mt);
      ++n_targets;
    }
  }
  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  if (n_targets > 0) h_delta = add_morph_targets(mesh);
  rep.morph_targets = n_targets;

  // OpenMesh prints a line per refused face; we handle and count those ourselves.
  struct QuietOmerr {
    QuietOmerr() { omerr().disable(); }
    ~QuietOmerr() { omerr().enable(); }
  } quiet;
  std::unordered_map<WeldKey, SkinnedMesh::VertexHandle, WeldHash> weld;
  std::vector<SkinnedMesh::VertexHandle> corner_vh;
  for (size_t ii = 0; ii < instances.size(); ++ii) {
    const Instance& in = instances[ii];
    const aiMesh* am = scene->mMeshes[in.mesh];
    ++rep.source_meshes;
    rep.source_vertices += am->mNumVertices;

    // The mesh's bind space: where a viewer shows it in the rest pose. Unskinned, that is its node's
    // world matrix; skinned, the glTF rule gives sum_k w_k J_k O_k v, and for a well-formed skin every
    // bone gives the same J_k O_k. Files whose rest pose is not their bind pose for some bones (FBX) give
    // several: take the one that carries the most skin weight, which is also the one a round trip
    // through our own export maps to identity. Vertices are stored there and each bone's inverse bind
    // becomes O_k B^-1, so posing J_k(t) O_k B^-1 (B v) is exact whichever was chosen.
    Eigen::Matrix4d B = sn.global[in.node];
    {
      std::vector<std::pair<Eigen::Matrix4d, double>> spaces;  // candidate, weight agreeing with it
      for (unsigned b = 0; b < am->mNumBones; ++b) {
        const aiBone* bone = am->mBones[b];
        const Eigen::Matrix4d c = sn.global[bone_node(bone)] * to_matrix(bone->mOffsetMatrix);
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
      const auto best = std::max_element(spaces.begin(), spaces.end(),
                                         [](const auto& x, const auto& y) { return x.second < y.second; });
      if (best != spaces.end()) B = best->first;
    }
    if (!B.allFinite() || std::abs(B.topLeftCorner<3, 3>().determinant()) < 1e-300)
      throw fail(std::string("mesh \"") + am->mName.C_Str() + "\" has a singular or non-finite bind transform");
    const Eigen::Matrix4d B_inv = B.inverse();
    const Eigen::Matrix3d normal_matrix = B.topLeftCorner<3, 3>().inverse().transpose();
    const int node_joint = joint_for(in.node, sn.global[in.node].inverse());

    std::vector<Influences> inf(am->mNumVertices);
    std::vector<char> touched(am->mNumVertices, 0);
    std::vector<size_t> over_capacity;
    for (unsigned b = 0; b < am->mNumBones; ++b) {
      const aiBone* bone = am->mBones[b];
      const int j = joint_for(bone_node(bone), to_matrix(bone->mOffsetMatrix) * B_inv);
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
        if (!vi.add_keeping_heaviest(j, wt)) over_capacity.push_back(vw.mVertexId);
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
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw fail("vertex " + std::to_string(v) + " of mesh \"" + am->mName.C_Str() + "\" has a non-finite position");
      const Eigen::Vector3d q = (B * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
      WeldKey key{{q.x(), q.y(), q.z()}, vi, {}};
      if (n_targets > 0) {
        key.deltas.assign(n_targets, Eigen::Vector3f::Zero());
        for (unsigned t = 0; t < am->mNumAnimMeshes; ++t) {
          const aiAnimMesh* an = am->mAnimMeshes[t];
          if (!an->mVertices) continue;  // a target of normals only: no offset
          const aiVector3D d = an->mVertices[v] - p;  // assimp stores the target's positions, not offsets
          const Eigen::Vector3d bd = B.topLeftCorner<3, 3>() * Eigen::Vector3d(d.x, d.y, d.z);
          if (!bd.allFinite()) throw fail("morph target " + std::to_string(t) + " has a non-finite position at vertex " + std::to_string(v));
          key.deltas[target_base[ii] + t] = bd.cast<float>();
        }
      }
      auto it = weld.find(key);
      if (it == weld.end()) {
        const auto vh = mesh.add_vertex(SkinnedMesh::Point(q.x(), q.y(), q.z()));
        mesh.property(h_inf, vh) = vi;
        if (n_targets > 0) mesh.property(h_delta, vh) = key.deltas;
        it = weld.emplace(std::move(key), vh).first;
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
        for (auto& vh : corner_vh) vh = copy_vertex(mesh, vh);
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
          // OpenMesh leaves attributes uninitialised: a mesh without normals or UVs gets zeros (a zero
          // normal is recomputed from the faces on export; all-zero UVs are not written).
          Eigen::Vector3d en = Eigen::Vector3d::Zero();
          if (has_n) {
            const aiVector3D& n = am->mNormals[src];
            en = normal_matrix * Eigen::Vector3d(n.x, n.y, n.z);
            if (!en.allFinite() || en.norm() == 0.0) en.setZero();
            else en.normalize();
          }
          mesh.set_normal(heh, SkinnedMesh::Normal(en.x(), en.y(), en.z()));
          SkinnedMesh::TexCoord2D uv(0, 0);
          if (has_uv) {
            const aiVector3D& t = am->mTextureCoords[0][src];
            if (std::isfinite(t.x) && std::isfinite(t.y)) uv = SkinnedMesh::TexCoord2D(t.x, t.y);
          }
          mesh.set_texcoord2D(heh, uv);
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
    rep.warnings.push_back(std::to_string(rep.degenerate_faces_skipped) +
                           " degenerate triangles (a repeated vertex) skipped");
  if (rep.twin_joints > 0)
    rep.warnings.push_back(std::to_string(rep.twin_joints) +
                           " joints are bound differently by different skins: each such skin got twin joints");

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
  for (auto fh : mesh.faces()) {
    const auto n = mesh.normal(fh);
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) mesh.set_normal(fh, SkinnedMesh::Normal(0, 0, 0));
  }
  rep.zero_area_faces = 0;
  for (auto fh : mesh.faces()) rep.zero_area_faces += mesh.calc_face_area(fh) == 0.0;
  if (rep.zero_area_faces > 0)
    rep.warnings.push_back(std::to_string(rep.zero_area_faces) +
                           " triangles have zero area (kept; the decimater removes them first)");

  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    const aiAnimation* an = scene->mAnimations[a];
    const double tps = an->mTicksPerSecond > 0.0 ? an->mTicksPerSecond : 25.0;
    Clip clip;
    clip.name = an->mName.length > 0 ? an->mName.C_Str() : "clip" + std::to_string(a);
    clip.duration = an->mDuration / tps;
    for (unsigned c = 0; c < an->mNumChannels; ++c) {
      const aiNodeAnim* na = an->mChannels[c];
      auto it = sn.by_name.find(na->mNodeName.C_Str());
      if (it == sn.by_name.end() || joints_of_node[it->second].empty()) continue;  // moves nothing we keep
      Channel ch;
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
      for (int j : joints_of_node[it->second]) {  // twins move with their node
        ch.joint = j;
        clip.channels.push_back(ch);
      }
    }
    // Morph weight channels are named after the node whose mesh they animate.
    for (unsigned c = 0; c < an->mNumMorphMeshChannels; ++c) {
      const aiMeshMorphAnim* ma = an->mMorphMeshChannels[c];
      std::string node_name = ma->mName.C_Str();
      if (node_name.find('*') != std::string::npos) node_name = node_name.substr(0, node_name.find('*'));
      bool used = false;
      for (size_t ii = 0; ii < instances.size(); ++ii) {
        if (sn.nodes[instances[ii].node]->mName.C_Str() != node_name) continue;
        const unsigned nt = scene->mMeshes[instances[ii].mesh]->mNumAnimMeshes;
        for (unsigned t = 0; t < nt; ++t) {
          MorphChannel mc;
          mc.target = static_cast<int>(target_base[ii] + t);
          for (unsigned k = 0; k < ma->mNumKeys; ++k) {
            const aiMeshMorphKey& key = ma->mKeys[k];
            double w = 0.0;
            for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j)
              if (key.mValues[j] == t) w = key.mWeights[j];
            mc.times.push_back(key.mTime / tps);
            mc.weights.push_back(w);
            clip.duration = std::max(clip.duration, key.mTime / tps);
          }
          if (!mc.times.empty()) clip.morph_channels.push_back(std::move(mc));
        }
        used = true;
      }
      if (!used)
        rep.warnings.push_back("clip \"" + clip.name + "\": morph channel \"" + node_name +
                               "\" names no mesh node: not kept");
    }
    clips(mesh).push_back(std::move(clip));
  }
  rep.clips = clips(mesh).size();
  example_poses(mesh) = {Pose::identity(skel.size())};
  for (const std::string& m : log.data_loss()) rep.warnings.push_back("the reader dropped data: " + m);

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
