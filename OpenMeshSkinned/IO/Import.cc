#include "OpenMeshSkinned/IO/Import.hh"

#include "OpenMeshSkinned/IO/GltfRepair.hh"
#include "OpenMeshSkinned/IO/GltfValueCheck.hh"
#include "OpenMeshSkinned/IO/ImportGeometry.hh"
#include "OpenMeshSkinned/IO/ImportMaterial.hh"
#include "OpenMeshSkinned/IO/ImportScene.hh"
#include "OpenMeshSkinned/IO/InputCheck.hh"
#include "OpenMeshSkinned/IO/IsolatedImport.hh"
#include "OpenMeshSkinned/IO/PrintableText.hh"
#include "OpenMeshSkinned/IO/ReaderLog.hh"
#include "OpenMeshSkinned/IO/StoredFrames.hh"
#include "OpenMeshSkinned/Mesh/NonManifold.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Skin/Validate.hh"

#include <OpenMesh/Core/System/omstream.hh>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace OpenMeshSkinned {
namespace {

using namespace detail;

// assimp's reading, its error made one line of a readable length: a reader may quote half the file back.
const aiScene* read_scene(Assimp::Importer& importer, const std::string& path, const std::string& read_path,
                          int frame) {
  if (frame >= 0) importer.SetPropertyInteger(AI_CONFIG_IMPORT_GLOBAL_KEYFRAME, frame);
  // FBX pivots folded into their nodes: the skeleton is the file's own bones, without the reader's
  // "$AssimpFbx$" helper nodes (which no engine sharing a skeleton across LODs, or retargeting by name, knows).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  // No PreTransformVertices or OptimizeGraph: both would destroy the skeleton we need.
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(read_path, flags);
  if (!scene) {
    throw IOError(path + ": cannot be read: " + printable_line(importer.GetErrorString()));
  }
  if (!scene->mRootNode || scene->mNumMeshes == 0) throw IOError(path + ": contains no mesh");
  // Skeleton-only files (BVH, MD5 anim) get a stand-in mesh of boxes around the bones from assimp.
  bool stand_in = scene->mNumMaterials > 0;
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    aiString name;
    stand_in &= scene->mMaterials[m]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS &&
                std::string(name.C_Str()) == "SkeletonMaterial";
  }
  if (stand_in) throw IOError(path + ": contains no mesh, only a skeleton and its animation (nothing to decimate)");
  return scene;
}

// ImportOptions::all_stored_frames and frame_files: the other frames' vertices as morph targets of the
// first frame's meshes, which must match them mesh for mesh, vertex for vertex and face for face.
void attach_frames(aiScene* scene, const std::string& path, const ImportOptions& opt) {
  const size_t n = opt.all_stored_frames ? stored_frame_count(path) : opt.frame_files.size() + 1;
  std::vector<std::vector<aiAnimMesh*>> added(scene->mNumMeshes);
  for (size_t f = 1; f < n; ++f) {
    const std::string file = opt.all_stored_frames ? path : opt.frame_files[f - 1];
    const std::string what = opt.all_stored_frames ? path + ": frame " + std::to_string(f) : file;
    Assimp::Importer other;
    const aiScene* s = read_scene(other, file, file, opt.all_stored_frames ? int(f) : -1);
    auto differs = [&](const std::string& how) {
      return IOError(what + ": not the same mesh as the first frame (" + how +
                     "): every frame must have the same vertices and faces");
    };
    if (s->mNumMeshes != scene->mNumMeshes) throw differs(std::to_string(s->mNumMeshes) + " meshes");
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh *a = scene->mMeshes[m], *b = s->mMeshes[m];
      if (a->mNumVertices != b->mNumVertices || a->mNumFaces != b->mNumFaces)
        throw differs("mesh " + std::to_string(m) + " has " + std::to_string(b->mNumVertices) + " vertices and " +
                      std::to_string(b->mNumFaces) + " faces");
      for (unsigned i = 0; i < a->mNumFaces; ++i)
        if (a->mFaces[i].mNumIndices != b->mFaces[i].mNumIndices ||
            !std::equal(a->mFaces[i].mIndices, a->mFaces[i].mIndices + a->mFaces[i].mNumIndices, b->mFaces[i].mIndices))
          throw differs("face " + std::to_string(i) + " of mesh " + std::to_string(m) + " has other vertices");
      auto* am = new aiAnimMesh();
      added[m].push_back(am);
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu", f);
      am->mName = name;
      am->mNumVertices = b->mNumVertices;
      am->mVertices = new aiVector3D[b->mNumVertices];
      std::copy(b->mVertices, b->mVertices + b->mNumVertices, am->mVertices);
    }
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    aiMesh* a = scene->mMeshes[m];
    if (added[m].empty()) continue;
    auto** all = new aiAnimMesh*[a->mNumAnimMeshes + added[m].size()];
    std::copy(a->mAnimMeshes, a->mAnimMeshes + a->mNumAnimMeshes, all);
    std::copy(added[m].begin(), added[m].end(), all + a->mNumAnimMeshes);
    delete[] a->mAnimMeshes;
    a->mAnimMeshes = all;
    a->mNumAnimMeshes += unsigned(added[m].size());
  }
}

// Morph targets of every mesh instance, numbered one after the other; returns where each instance's start.
// Instances of one node with as many targets share them: they are the primitives of one glTF mesh (which
// must all have the same targets, moved by the node's one set of weights), or the meshes of one node that
// its clips' weight channels move together; numbering them apart would multiply the targets.
std::vector<size_t> read_morph_targets(const aiScene* scene, const std::vector<MeshInstance>& instances,
                                       SkinnedMesh& mesh, const std::string& path) {
  std::vector<size_t> target_base(instances.size(), 0);
  for (size_t ii = 0; ii < instances.size(); ++ii) {
    const aiMesh* am = scene->mMeshes[instances[ii].mesh];
    for (unsigned t = 0; t < am->mNumAnimMeshes; ++t)
      if (am->mAnimMeshes[t]->mNumVertices != am->mNumVertices)
        throw IOError(path + ": morph target " + std::to_string(t) + " of mesh \"" + am->mName.C_Str() + "\" has " +
                      std::to_string(am->mAnimMeshes[t]->mNumVertices) + " vertices, the mesh " +
                      std::to_string(am->mNumVertices));
    target_base[ii] = morph_targets(mesh).size();
    bool shared = false;
    for (size_t jj = 0; jj < ii && !shared; ++jj)
      if (instances[jj].node == instances[ii].node && am->mNumAnimMeshes > 0 &&
          scene->mMeshes[instances[jj].mesh]->mNumAnimMeshes == am->mNumAnimMeshes)
        target_base[ii] = target_base[jj], shared = true;
    if (shared) continue;
    for (unsigned t = 0; t < am->mNumAnimMeshes; ++t) {
      const aiAnimMesh* an = am->mAnimMeshes[t];
      MorphTarget mt;
      mt.name = an->mName.length ? an->mName.C_Str() : std::string(am->mName.C_Str()) + "_target" + std::to_string(t);
      morph_targets(mesh).push_back(mt);
    }
  }
  if (!morph_targets(mesh).empty()) add_morph_targets(mesh);
  return target_base;
}

// What the geometry steps did, as warnings; then the clean-up the decimater relies on.
void finish_mesh(SkinnedMesh& mesh, ImportReport& rep, const std::string& path) {
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  const auto h_fmat = face_material_handle(mesh);
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
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]))
      mesh.set_normal(fh, SkinnedMesh::Normal(0, 0, 0));
  }
  rep.zero_area_faces = 0;
  for (auto fh : mesh.faces()) rep.zero_area_faces += mesh.calc_face_area(fh) == 0.0;
  if (rep.zero_area_faces > 0)
    rep.warnings.push_back(std::to_string(rep.zero_area_faces) +
                           " triangles have zero area (kept; the decimater removes them first)");
}

}  // namespace

ImportReport import_skinned(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  std::error_code ec;
  if (!fs::exists(path, ec)) throw fail("file does not exist");
  if (fs::is_directory(path, ec)) throw fail("is a directory, not a file");
  if (fs::file_size(path, ec) == 0) throw fail("file is empty");
  // The child repairs and decodes too: a decoder reads sizes and streams from the file, as a reader does.
  if (opt.isolate) return import_isolated(path, mesh, opt, &detail::import_file);
  return detail::import_file(path, mesh, opt);
}

ImportReport detail::import_file(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt) {
  const RepairedGltf repaired(path);
  ImportReport rep = import_scene(path, repaired.path().empty() ? path : repaired.path(), mesh, opt);
  rep.warnings.insert(rep.warnings.begin(), repaired.notes().begin(), repaired.notes().end());
  return rep;
}

ImportReport detail::import_scene(const std::string& path, const std::string& read_path, SkinnedMesh& mesh,
                                  const ImportOptions& opt) {
  namespace fs = std::filesystem;
  check_gltf_values(read_path, path);
  const ReaderLog log;
  Assimp::Importer importer;
  const aiScene* scene = read_scene(importer, path, read_path, opt.frame);
  if (opt.all_stored_frames || !opt.frame_files.empty()) attach_frames(const_cast<aiScene*>(scene), path, opt);
  const SceneNodes sn(scene->mRootNode);
  const std::vector<MeshInstance> instances = mesh_instances(scene, sn);
  if (instances.empty()) throw IOError(path + ": contains no triangle mesh");

  ImportReport rep;
  mesh = SkinnedMesh();  // a fresh mesh: clear() would keep the properties (skeleton, clips) of an earlier use
  request_skinned_attributes(mesh);
  add_skin(mesh);
  face_material_handle(mesh);
  JointMap joints(scene, sn, instances, skeleton(mesh), path);
  rep.rigid = !joints.any_bones();
  if (rep.rigid) rep.warnings.push_back("no skin in the file: every mesh is bound rigidly to its node");

  materials(mesh) = read_materials(scene, path, read_path, rep.warnings);
  const std::vector<size_t> target_base = read_morph_targets(scene, instances, mesh, path);
  rep.morph_targets = morph_targets(mesh).size();
  {
    // OpenMesh prints a line per refused face; we handle and count those ourselves.
    struct QuietOmerr {
      QuietOmerr() { omerr().disable(); }
      ~QuietOmerr() { omerr().enable(); }
    } quiet;
    // Reserved up front, as the archive reader does: grown by doubling, every array and per-element property
    // would keep up to half its capacity unused for the whole run.
    size_t nv = 0, nf = 0;
    for (const MeshInstance& mi : instances) {
      nv += scene->mMeshes[mi.mesh]->mNumVertices;
      nf += scene->mMeshes[mi.mesh]->mNumFaces;
    }
    mesh.reserve(nv + nv / 32 + 16, nf + nf / 2 + nf / 32 + 16, nf);
    GeometryBuilder geometry(mesh, rep.morph_targets, opt, rep, path);
    geometry.reserve(nv);
    for (size_t ii = 0; ii < instances.size(); ++ii) geometry.add(scene, sn, joints, instances[ii], target_base[ii]);
  }
  rep.twin_joints = joints.twins();
  finish_mesh(mesh, rep, path);
  bool morph_channels = false;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a)
    morph_channels |= scene->mAnimations[a]->mNumMorphMeshChannels > 0;
  read_clips(scene, sn, joints, instances, target_base,
             morph_channels ? read_signed_morph_weights(read_path, rep.warnings) : detail::SignedMorphWeights(), mesh,
             rep.warnings);
  rep.clips = clips(mesh).size();
  check_input(mesh, path, rep.warnings);
  for (const std::string& m : log.data_loss()) rep.warnings.push_back("the reader dropped data: " + m);
  try {
    ValidationOptions vo;
    vo.sum_tolerance = opt.sum_tolerance;
    validate_skin(mesh, vo);
  } catch (const SkinError& e) {
    throw IOError(path + ": " + e.what());
  }
  return rep;
}

}  // namespace OpenMeshSkinned
