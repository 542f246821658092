#include "OpenMeshSkinned/IO/GltfValueCheck.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace OpenMeshSkinned {
namespace {

// Images are irrelevant here and decoding them would only cost time.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

void check_gltf_weights(const std::string& path, const std::string& shown_as) {
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
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (const auto& prim : model.meshes[m].primitives)
      for (const auto& [name, index] : prim.attributes) {
        if (name.rfind("WEIGHTS_", 0) != 0 || index < 0 || size_t(index) >= model.accessors.size()) continue;
        const auto& acc = model.accessors[index];
        if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc.bufferView < 0 ||
            size_t(acc.bufferView) >= model.bufferViews.size())
          continue;  // normalised integers cannot be non-finite
        const auto& view = model.bufferViews[acc.bufferView];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) continue;
        const auto& data = model.buffers[view.buffer].data;
        const size_t comps = 4, stride = view.byteStride ? view.byteStride : comps * sizeof(float);
        const size_t start = view.byteOffset + acc.byteOffset;
        for (size_t v = 0; v < acc.count; ++v)
          for (size_t c = 0; c < comps; ++c) {
            const size_t at = start + v * stride + c * sizeof(float);
            if (at + sizeof(float) > data.size()) break;  // out of bounds: tinygltf's and assimp's business
            float w;
            std::memcpy(&w, data.data() + at, sizeof w);
            if (!std::isfinite(w) || w < 0.0f)
              throw IOError(shown_as + ": vertex " + std::to_string(v) + " of mesh " + std::to_string(m) + " (\"" +
                            model.meshes[m].name + "\") has a " + (w < 0.0f ? "negative" : "non-finite") +
                            " weight in " + name);
          }
      }
}

}  // namespace OpenMeshSkinned
