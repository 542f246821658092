#include "OpenMeshSkinned/IO/ExportParts.hh"

#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>

namespace OpenMeshSkinned::detail {

void write_clips(const SkinnedMesh& mesh, int mesh_node, BufferWriter& buf, tinygltf::Model& model) {
  OpenMesh::VPropHandleT<MorphDeltas> h_delta;
  const size_t n_targets = morph_deltas_handle(mesh, h_delta) ? morph_targets(mesh).size() : 0;
  for (const Clip& clip : clips(mesh)) {
    tinygltf::Animation anim;
    anim.name = clip.name;
    // \p count output elements: one per key, except for morph weights (one per key and target).
    auto add_sampler = [&](const std::vector<double>& times, const std::vector<float>& values, int type, size_t count,
                           int node, const char* path_name) {
      if (times.empty()) return;
      std::vector<float> t(times.begin(), times.end());
      const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
      tinygltf::AnimationSampler s;
      s.input = buf.add(t, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, t.size(), 0, {*lo}, {*hi});
      s.output = buf.add(values, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count, 0);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
      ch.target_node = node;
      ch.target_path = path_name;
      anim.channels.push_back(ch);
    };
    for (const Channel& ch : clip.channels) {
      std::vector<float> tr, ro, sc;
      for (const auto& v : ch.translations) tr.insert(tr.end(), {float(v.x()), float(v.y()), float(v.z())});
      for (const auto& q : ch.rotations) {
        const Eigen::Quaterniond u = q.normalized();
        ro.insert(ro.end(), {float(u.x()), float(u.y()), float(u.z()), float(u.w())});
      }
      for (const auto& v : ch.scales) sc.insert(sc.end(), {float(v.x()), float(v.y()), float(v.z())});
      add_sampler(ch.translation_times, tr, TINYGLTF_TYPE_VEC3, ch.translation_times.size(), ch.joint, "translation");
      add_sampler(ch.rotation_times, ro, TINYGLTF_TYPE_VEC4, ch.rotation_times.size(), ch.joint, "rotation");
      add_sampler(ch.scale_times, sc, TINYGLTF_TYPE_VEC3, ch.scale_times.size(), ch.joint, "scale");
    }
    if (n_targets > 0 && !clip.morph_channels.empty()) {
      // glTF animates all of a mesh's weights in one channel: sample every target at the union of the keys.
      std::vector<double> times;
      for (const MorphChannel& mc : clip.morph_channels) times.insert(times.end(), mc.times.begin(), mc.times.end());
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end()), times.end());
      std::vector<float> w;
      for (double t : times) {
        std::vector<double> at = sample_morph_weights(clip, t);
        at.resize(n_targets, 0.0);
        w.insert(w.end(), at.begin(), at.end());
      }
      add_sampler(times, w, TINYGLTF_TYPE_SCALAR, w.size(), mesh_node, "weights");
    }
    if (!anim.channels.empty()) model.animations.push_back(anim);
  }
}

}  // namespace OpenMeshSkinned::detail
