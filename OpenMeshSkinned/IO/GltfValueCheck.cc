#include "OpenMeshSkinned/IO/GltfValueCheck.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <vector>

namespace OpenMeshSkinned {
namespace {

// Images are irrelevant here and decoding them would only cost time.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// An accessor's elements as bytes of its buffer, checked to lie inside its view and the view inside its
// buffer: a corrupt count (2^31 elements) must not read the rest of the buffer as weights. A sparse
// accessor's substituted elements are checked the same way, and its indices to lie within its count.
struct Elements {
  const unsigned char* data = nullptr;  // the base elements; null: all zero (a sparse accessor without a view)
  size_t count = 0, stride = 0, component = 0;
  int components = 0;
  std::map<size_t, const unsigned char*> sparse;  // element index -> its substitute

  const unsigned char* at(size_t v, int c) const {
    if (const auto it = sparse.find(v); it != sparse.end()) return it->second + size_t(c) * component;
    return data ? data + v * stride + size_t(c) * component : nullptr;
  }
  /// The elements that can be other than zero: every one, or only the substitutes when there is no base.
  std::vector<size_t> nonzero() const {
    std::vector<size_t> v;
    if (data)
      for (size_t i = 0; i < count; ++i) v.push_back(i);
    else
      for (const auto& [i, p] : sparse) v.push_back(i);
    return v;
  }
};

// The bytes of \p n items of \p size bytes at \p offset in buffer view \p view_index, checked to lie in the
// view and the view in its buffer; \p fail names the accessor in the error.
template <typename Fail>
const unsigned char* view_bytes(const tinygltf::Model& model, int view_index, size_t offset, size_t n, size_t size,
                                size_t stride, const std::string& part, const Fail& fail) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    throw fail("has " + part + " in buffer view " + std::to_string(view_index) + ", which does not exist");
  const auto& view = model.bufferViews[view_index];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    throw fail("has " + part + " in a buffer view of buffer " + std::to_string(view.buffer) + ", which does not exist");
  const size_t buffer_size = model.buffers[view.buffer].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset)
    throw fail("lies in a buffer view of " + std::to_string(view.byteLength) + " bytes at " +
               std::to_string(view.byteOffset) + " that reaches past its buffer's " + std::to_string(buffer_size));
  // In items, so that the product cannot overflow: n - 1 strides and one item must fit.
  const bool fits = offset <= view.byteLength && size <= view.byteLength - offset &&
                    (n == 0 || (n - 1) <= (view.byteLength - offset - size) / stride);
  if (!fits)
    throw fail("claims " + std::to_string(n) + " " + part + " of " + std::to_string(size) + " bytes from byte " +
               std::to_string(offset) + ", more than its buffer view's " + std::to_string(view.byteLength) +
               " bytes hold");
  return model.buffers[view.buffer].data.data() + view.byteOffset + offset;
}

bool elements(const tinygltf::Model& model, int index, const std::string& what, const std::string& shown_as,
              Elements& out) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return false;
  const auto& acc = model.accessors[index];
  const bool sparse = acc.sparse.isSparse;
  if (!sparse && (acc.bufferView < 0 || size_t(acc.bufferView) >= model.bufferViews.size())) return false;
  const int comp_size = tinygltf::GetComponentSizeInBytes(acc.componentType);
  const int n_comp = tinygltf::GetNumComponentsInType(acc.type);
  if (comp_size <= 0 || n_comp <= 0) return false;
  out.component = size_t(comp_size);
  out.components = n_comp;
  const size_t elem = out.component * size_t(n_comp);
  out.count = acc.count;
  const auto fail = [&](const std::string& problem) {
    return IOError(shown_as + ": accessor " + std::to_string(index) + " (" + what + ") " + problem);
  };
  if (acc.bufferView >= 0) {
    const size_t view_stride =
        size_t(acc.bufferView) < model.bufferViews.size() ? model.bufferViews[acc.bufferView].byteStride : 0;
    out.stride = view_stride ? view_stride : elem;
    out.data = view_bytes(model, acc.bufferView, acc.byteOffset, acc.count, elem, out.stride, "elements", fail);
  }
  if (!sparse) return true;
  const auto& sp = acc.sparse;
  if (sp.count < 1 || size_t(sp.count) > acc.count)
    throw fail("is sparse with " + std::to_string(sp.count) + " substitutes for its " + std::to_string(acc.count) +
               " elements");
  const int index_size = tinygltf::GetComponentSizeInBytes(sp.indices.componentType);
  if (sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw fail("has sparse indices of component type " + std::to_string(sp.indices.componentType) +
               ", not an unsigned integer type");
  const size_t n = size_t(sp.count);
  const unsigned char* idx = view_bytes(model, sp.indices.bufferView, size_t(sp.indices.byteOffset), n,
                                        size_t(index_size), size_t(index_size), "sparse indices", fail);
  const unsigned char* val =
      view_bytes(model, sp.values.bufferView, size_t(sp.values.byteOffset), n, elem, elem, "sparse values", fail);
  size_t previous = 0;
  for (size_t k = 0; k < n; ++k) {
    uint32_t i = 0;
    if (index_size == 1) i = idx[k];
    if (index_size == 2) {
      uint16_t u;
      std::memcpy(&u, idx + 2 * k, 2);
      i = u;
    }
    if (index_size == 4) std::memcpy(&i, idx + 4 * k, 4);
    if (i >= acc.count)
      throw fail("substitutes element " + std::to_string(i) + " (sparse entry " + std::to_string(k) + ") of its " +
                 std::to_string(acc.count));
    // The spec's rule: readers that patch in order would otherwise disagree on which substitute wins.
    if (k > 0 && i <= previous)
      throw fail("has sparse indices that do not increase (entry " + std::to_string(k) + ": " + std::to_string(i) +
                 " after " + std::to_string(previous) + ")");
    previous = i;
    out.sparse[i] = val + k * elem;
  }
  return true;
}

double component(const Elements& e, size_t v, int c, int type) {
  const unsigned char* p = e.at(v, c);
  if (!p) return 0.0;
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
        if (name == "POSITION") {
          // The reader patches sparse positions in place: their indices must lie inside (the values
          // are checked once read, as every position is).
          Elements e;
          elements(model, index, name + " of " + mesh_name, shown_as, e);
          continue;
        }
        if (!weights && name.rfind("JOINTS_", 0) != 0) continue;
        Elements e;
        if (!elements(model, index, name + " of " + mesh_name, shown_as, e)) continue;
        const int type = model.accessors[index].componentType;
        if (weights) {
          if (type != TINYGLTF_COMPONENT_TYPE_FLOAT) continue;  // normalised integers cannot be non-finite
          for (size_t v : e.nonzero())
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
        // A weight is 0 where neither accessor has a base or a substitute.
        std::vector<size_t> visit = e.nonzero();
        if (!e.data) {
          for (size_t v : w.nonzero())
            if (!e.sparse.count(v)) visit.push_back(v);
        }
        for (size_t v : visit) {
          if (v >= std::min(e.count, w.count)) continue;
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
}

}  // namespace OpenMeshSkinned
