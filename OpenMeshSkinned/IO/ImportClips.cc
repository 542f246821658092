#include "OpenMeshSkinned/IO/ImportScene.hh"

#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>

namespace OpenMeshSkinned::detail {

namespace {

// Keys relative to a node's parent node made relative to its parent joint, through the similarity
// \p folded of the ancestors between them (JointMap): folded * T R S = T' R' S' exactly.
void fold_keys(Channel& ch, const Eigen::Matrix4d& folded) {
  Eigen::Vector3d t, s;
  Eigen::Quaterniond r;
  decompose_trs(folded, t, r, s);
  const double scale = s.x();  // a similarity: s is uniform
  for (Eigen::Vector3d& v : ch.translations) v = (folded * v.homogeneous()).head<3>();
  for (Eigen::Quaterniond& q : ch.rotations) q = r * q;
  for (Eigen::Vector3d& v : ch.scales) v *= scale;
}

// One node's keys, in seconds; the clip lasts at least until its last key.
Channel read_channel(const aiNodeAnim* na, double tps, double& duration) {
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
  for (double t : ch.translation_times) duration = std::max(duration, t);
  for (double t : ch.rotation_times) duration = std::max(duration, t);
  for (double t : ch.scale_times) duration = std::max(duration, t);
  return ch;
}

}  // namespace

void read_clips(const aiScene* scene, const SceneNodes& sn, const JointMap& joints,
                const std::vector<MeshInstance>& instances, const std::vector<size_t>& target_base,
                const SignedMorphWeights& signed_weights, SkinnedMesh& mesh, std::vector<std::string>& warnings) {
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    const aiAnimation* an = scene->mAnimations[a];
    const double tps = an->mTicksPerSecond > 0.0 ? an->mTicksPerSecond : 25.0;
    Clip clip;
    clip.name = an->mName.length > 0 ? an->mName.C_Str() : "clip" + std::to_string(a);
    clip.duration = an->mDuration / tps;
    for (unsigned c = 0; c < an->mNumChannels; ++c) {
      const aiNodeAnim* na = an->mChannels[c];
      auto it = sn.by_name.find(na->mNodeName.C_Str());
      if (it == sn.by_name.end() || joints.joints_of_node(it->second).empty()) continue;  // moves nothing we keep
      Channel ch = read_channel(na, tps, clip.duration);
      if (!joints.folded_above(it->second).isIdentity(0.0)) fold_keys(ch, joints.folded_above(it->second));
      for (int j : joints.joints_of_node(it->second)) {  // twins move with their node
        ch.joint = j;
        clip.channels.push_back(ch);
      }
    }
    // Morph weight channels are named after the node whose mesh they animate.
    for (unsigned c = 0; c < an->mNumMorphMeshChannels; ++c) {
      const aiMeshMorphAnim* ma = an->mMorphMeshChannels[c];
      std::string node_name = ma->mName.C_Str();
      if (node_name.find('*') != std::string::npos) node_name = node_name.substr(0, node_name.find('*'));
      const SignedMorphWeights::Channel* file = signed_weights.find(a, node_name);
      const size_t file_targets = file && file->keys == ma->mNumKeys ? file->values.size() / file->keys : 0;
      bool used = false;
      for (size_t ii = 0; ii < instances.size(); ++ii) {
        if (sn.nodes[instances[ii].node]->mName.C_Str() != node_name) continue;
        const unsigned nt = scene->mMeshes[instances[ii].mesh]->mNumAnimMeshes;
        for (unsigned t = 0; t < nt; ++t) {
          MorphChannel mc;
          mc.target = static_cast<int>(target_base[ii] + t);
          // Instances sharing their targets (one glTF mesh's primitives) share the channel too.
          if (std::any_of(clip.morph_channels.begin(), clip.morph_channels.end(),
                          [&](const MorphChannel& o) { return o.target == mc.target; }))
            continue;
          for (unsigned k = 0; k < ma->mNumKeys; ++k) {
            const aiMeshMorphKey& key = ma->mKeys[k];
            double w = 0.0;
            for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j)
              if (key.mValues[j] == t) w = key.mWeights[j];
            if (t < file_targets) w = file->values[k * file_targets + t];
            mc.times.push_back(key.mTime / tps);
            mc.weights.push_back(w);
            clip.duration = std::max(clip.duration, key.mTime / tps);
          }
          if (!mc.times.empty()) clip.morph_channels.push_back(std::move(mc));
        }
        used = true;
      }
      if (!used)
        warnings.push_back("clip \"" + clip.name + "\": morph channel \"" + node_name +
                           "\" names no mesh node: not kept");
    }
    clips(mesh).push_back(std::move(clip));
  }
}

}  // namespace OpenMeshSkinned::detail
