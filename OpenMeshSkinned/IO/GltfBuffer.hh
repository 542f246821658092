#pragma once
/** \file GltfBuffer.hh
 *  The one binary buffer of an exported glTF, filled view by view. Internal to the exporter.
 */

#include <tiny_gltf.h>

#include <cstring>
#include <vector>

namespace OpenMeshSkinned::detail {

// Appends raw bytes to the single buffer and returns an accessor over them.
class BufferWriter {
public:
  explicit BufferWriter(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  /// Appends raw bytes as a buffer view of their own (what images need) and returns its index.
  template <typename T>
  int add_view(const std::vector<T>& data, int target = 0) {
    auto& bytes = model_.buffers[0].data;
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t offset = bytes.size();
    const size_t n = data.size() * sizeof(T);
    bytes.resize(offset + n);
    if (n) std::memcpy(bytes.data() + offset, data.data(), n);

    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = n;
    if (target) view.target = target;
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  template <typename T>
  int add(const std::vector<T>& data, int component_type, int type, size_t count, int target,
          std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor acc;
    acc.bufferView = add_view(data, target);
    acc.componentType = component_type;
    acc.type = type;
    acc.count = count;
    acc.minValues = std::move(min);
    acc.maxValues = std::move(max);
    model_.accessors.push_back(acc);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

private:
  tinygltf::Model& model_;
};

}  // namespace OpenMeshSkinned::detail
