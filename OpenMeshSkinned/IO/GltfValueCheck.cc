#include "OpenMeshSkinned/IO/GltfValueCheck.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace OpenMeshSkinned {
namespace {

// Images are irrelevant here and decoding them would only cost time.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// An accessor's elements as bytes of its buffer, checked to lie inside its view and the view inside its
// buffer: a corrupt count (2^31 elements) must not read the rest of the buffer as weights.
struct Elements {
  const unsigned char* data = nullptr;
  size_t count = 0, stride = 0, component = 0;
  int components = 0;

  const unsigned char* at(size_t v, int c) const { return data + v * stride + size_t(c) * component; }
};

bool elements(const tinygltf::Model& model, int index, const std::string& what, const std::string& shown_as,
              Elements& out) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return false;
  const auto& acc = model.accessors[index];
  if (acc.bufferView < 0 || size_t(acc.bufferView) >= model.bufferViews.size() || acc.sparse.isSparse) return false;
  const auto& view = model.bufferViews[acc.bufferView];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) return false;
  const int comp_size = tinygltf::GetComponentSizeInBytes(acc.componentType);
  const int n_comp = tinygltf::GetNumComponentsInType(acc.type);
  if (comp_size <= 0 || n_comp <= 0) return false;
  out.component = size_t(comp_size);
  out.components = n_comp;
  const size_t elem = out.component * size_t(n_comp);
  out.stride = view.byteStride ? view.byteStride : elem;
  out.count = acc.count;
  const auto fail = [&](const std::string& problem) {
    return IOError(shown_as + ": accessor " + std::to_string(index) + " (" + what + ") " + problem);
  };
  const size_t buffer_size = model.buffers[view.buffer].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset)
    throw fail("lies in a buffer view of " + std::to_string(view.byteLength) + " bytes at " +
               std::to_string(view.byteOffset) + " that reaches past its buffer's " + std::to_string(buffer_size));
  // In elements, so that the product cannot overflow: count - 1 strides and one element must fit.
  const bool fits = acc.byteOffset <= view.byteLength && elem <= view.byteLength - acc.byteOffset &&
                    (acc.count == 0 || (acc.count - 1) <= (view.byteLength - acc.byteOffset - elem) / out.stride);
  if (!fits)
    throw fail("claims " + std::to_string(acc.count) + " elements of " + std::to_string(elem) + " bytes from byte " +
               std::to_string(acc.byteOffset) + ", more than its buffer view's " + std::to_string(view.byteLength) +
               " bytes hold");
  out.data = model.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset;
  return true;
}

double component(const Elements& e, size_t v, int c, int type) {
  const unsigned char* p = e.at(v, c);
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, sizeof f);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t u;
      std::memcpy(&u, p, sizeof u);
      return u;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t u;
      std::memcpy(&u, p, sizeof u);
      return u;
    }
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

void check_gltf_values(const std::string& path, const std::string& shown_as) {
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool glb = ext == ".glb" || ext == ".GLB";
  if (!glb && ext != ".gltf" && ext != ".GLTF") return;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok =
      glb ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) return;
  // The fewest joints of the skins the nodes using a mesh bind it with: an index must fit every one.
  std::vector<size_t> joints_of_mesh(model.meshes.size(), std::numeric_limits<size_t>::max());
  std::vector<std::string> skin_of_mesh(model.meshes.size());
  for (const auto& node : model.nodes)
    if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size() && node.skin >= 0 &&
        size_t(node.skin) < model.skins.size() && model.skins[node.skin].joints.size() < joints_of_mesh[node.mesh]) {
      joints_of_mesh[node.mesh] = model.skins[node.skin].joints.size();
      skin_of_mesh[node.mesh] = "skin " + std::to_string(node.skin) + " (\"" + model.skins[node.skin].name + "\")";
    }
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const std::string mesh_name = "mesh " + std::to_string(m) + " (\"" + model.meshes[m].name + "\")";
    for (const auto& prim : model.meshes[m].primitives)
      for (const auto& [name, index] : prim.attributes) {
        const bool weights = name.rfind("WEIGHTS_", 0) == 0;
        if (!weights && name.rfind("JOINTS_", 0) != 0) continue;
        Elements e;
        if (!elements(model, index, name + " of " + mesh_name, shown_as, e)) continue;
        const int type = model.accessors[index].componentType;
        if (weights) {
          if (type != TINYGLTF_COMPONENT_TYPE_FLOAT) continue;  // normalised integers cannot be non-finite
          for (size_t v = 0; v < e.count; ++v)
            for (int c = 0; c < e.components; ++c) {
              const double x = component(e, v, c, type);
              if (!std::isfinite(x) || x < 0.0)
                throw IOError(shown_as + ": vertex " + std::to_string(v) + " of " + mesh_name + " has a " +
                              (x < 0.0 ? "negative" : "non-finite") + " weight in " + name);
            }
          continue;
        }
        // A joint index counts only where its weight is not 0 (the spec's readers ignore the others).
        const std::string wname = "WEIGHTS_" + name.substr(7);
        const auto wi = prim.attributes.find(wname);
        if (joints_of_mesh[m] == std::numeric_limits<size_t>::max() || wi == prim.attributes.end()) continue;
        Elements w;
        if (!elements(model, wi->second, wname + " of " + mesh_name, shown_as, w)) continue;
        const int wtype = model.accessors[wi->second].componentType;
        for (size_t v = 0; v < std::min(e.count, w.count); ++v)
          for (int c = 0; c < std::min(e.components, w.components); ++c) {
            const double joint = component(e, v, c, type);
            if (component(w, v, c, wtype) != 0.0 && !(joint < double(joints_of_mesh[m])))
              throw IOError(shown_as + ": vertex " + std::to_string(v) + " of " + mesh_name + " names joint " +
                            std::to_string(static_cast<unsigned long long>(joint)) + " in " + name + ", but " +
                            skin_of_mesh[m] + " has " + std::to_string(joints_of_mesh[m]) + " joints");
          }
      }
  }
}

}  // namespace OpenMeshSkinned
