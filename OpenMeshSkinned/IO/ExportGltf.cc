#include "OpenMeshSkinned/IO/ExportGltf.hh"

#include "OpenMeshSkinned/IO/ExportMaterials.hh"
#include "OpenMeshSkinned/IO/ExportParts.hh"

#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <tiny_gltf.h>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>

namespace OpenMeshSkinned {
namespace {

void write_node_trs(tinygltf::Node& node, const Eigen::Matrix4d& local) {
  Eigen::Vector3d t, s;
  Eigen::Quaterniond r;
  decompose_trs(local, t, r, s);
  if (t.squaredNorm() > 0.0) node.translation = {t.x(), t.y(), t.z()};
  if (!r.coeffs().isApprox(Eigen::Vector4d(0, 0, 0, 1))) node.rotation = {r.x(), r.y(), r.z(), r.w()};
  if (!s.isApprox(Eigen::Vector3d::Ones())) node.scale = {s.x(), s.y(), s.z()};
}

// Nodes 0..J-1 are the joints, in skeleton order; returns the top-level ones.
std::vector<int> write_joint_nodes(const Skeleton& skel, tinygltf::Model& model) {
  for (const Joint& j : skel.joints) {
    tinygltf::Node node;
    // tinygltf writes a node with no name and an identity transform as null, which no reader accepts.
    node.name = j.name.empty() ? "joint" + std::to_string(model.nodes.size()) : j.name;
    write_node_trs(node, j.rest_local);
    model.nodes.push_back(node);
  }
  std::vector<int> roots;
  for (int i = 0; i < skel.size(); ++i) {
    const int p = skel.joints[i].parent;
    if (p < 0)
      roots.push_back(i);
    else
      model.nodes[p].children.push_back(i);
  }
  return roots;
}

void write_skin(const Skeleton& skel, detail::BufferWriter& buf, tinygltf::Model& model, const std::string& path) {
  tinygltf::Skin skin;
  skin.name = "skin";
  std::vector<float> ibm;
  for (const Joint& j : skel.joints) {
    if (!j.inverse_bind.allFinite())
      throw IOError(path + ": joint \"" + j.name + "\" has a non-finite inverse bind matrix");
    for (int c = 0; c < 4; ++c) {  // column-major; the last row exactly (0, 0, 0, 1), as the spec requires
      for (int r = 0; r < 3; ++r) ibm.push_back(static_cast<float>(j.inverse_bind(r, c)));
      ibm.push_back(c == 3 ? 1.0f : 0.0f);
    }
  }
  skin.inverseBindMatrices = buf.add(ibm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, skel.size(), 0);
  for (int i = 0; i < skel.size(); ++i) skin.joints.push_back(i);
  model.skins.push_back(skin);
}

// Node J holds the mesh, with \p node_extras; the scene holds it and the joints' roots.
void write_scene(int n_joints, const std::vector<int>& roots, const GltfNodeExtras& node_extras,
                 tinygltf::Model& model) {
  tinygltf::Node mesh_node;
  mesh_node.name = "skinned_mesh";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  if (!node_extras.empty()) {
    tinygltf::Value::Object extras;
    for (const auto& [name, value] : node_extras) extras[name] = tinygltf::Value(value);
    mesh_node.extras = tinygltf::Value(extras);
  }
  model.nodes.push_back(mesh_node);
  tinygltf::Scene scene;
  // A skin's joints must share a root: several top-level joints (two separate hierarchies in the input)
  // get a node above them that is no joint, so that the skin lists the input's joints and only those.
  if (roots.size() > 1) {
    tinygltf::Node common;
    common.name = "joints_root";
    common.children = roots;
    model.nodes.push_back(common);
    scene.nodes.push_back(n_joints + 1);
  } else {
    scene.nodes = roots;
  }
  scene.nodes.push_back(n_joints);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

// Write beside the target and rename: readers never see half a file, and a failure leaves nothing.
void write_atomically(tinygltf::Model& model, const std::string& path, const std::string& ext) {
  namespace fs = std::filesystem;
  auto fail = [&path](const std::string& what) -> IOError { return IOError(path + ": " + what); };
  std::error_code ec;
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

}  // namespace

void export_gltf(const SkinnedMesh& mesh, const std::string& path) { export_gltf(mesh, path, {}); }

void export_gltf(const SkinnedMesh& mesh, const std::string& path, const GltfNodeExtras& node_extras) {
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
  if (skel.size() == 0) throw fail("skeleton has no joints");
  if (skel.size() > 65535) throw fail("more than 65535 joints");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "OpenMeshSkinned";
  detail::BufferWriter buf(model);
  const std::vector<int> roots = write_joint_nodes(skel, model);
  write_skin(skel, buf, model, path);
  try {
    detail::write_materials(materials(mesh), detail::written_uv_sets(mesh), buf, model);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // a carried field of the wrong type (e.g. a string alphaCutoff)
    throw fail(std::string("cannot be written: a material field has the wrong type (") + e.what() + ")");
  }
  model.meshes.push_back(detail::write_mesh(mesh, buf, path));
  write_scene(skel.size(), roots, node_extras, model);
  detail::write_clips(mesh, skel.size(), buf, model);
  write_atomically(model, path, ext);
}

}  // namespace OpenMeshSkinned
