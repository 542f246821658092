#pragma once
/** \file GltfMorphWeights.hh
 *  The morph weight keys of a glTF 2.0 file's animations with their signs: assimp 5.2 clamps negative
 *  weights to 0 (a target driven below zero, as corrective shapes and blink rigs do, would stop at rest).
 *  Internal to the importer: read_clips() takes these in place of assimp's where a channel has any.
 */

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace OpenMeshSkinned::detail {

/// The "weights" channels of a glTF file that hold a negative weight, by animation and target node (but for
/// nodes whose name another node shares, whose channels assimp's names cannot tell apart).
struct SignedMorphWeights {
  struct Channel {
    size_t keys = 0;
    std::vector<double> values;  ///< per key, one weight per morph target
  };
  /// By (animation index, the node's name as assimp names it: its own, or "nodes[i]" when it has none).
  std::map<std::pair<size_t, std::string>, Channel> channels;

  /// The channel of \p animation moving \p node's weights; nullptr when it has no negative weight.
  const Channel* find(size_t animation, const std::string& node) const;
};

/** The signed weight channels of the glTF 2.0 file \p read_path (the copy assimp reads, whose samplers are
 *  all LINEAR: GltfInterpolation.hh); empty for any other file. When the animations cannot be read here, a
 *  line in \p warnings says that negative weights stay at 0 (assimp's reading stands). */
SignedMorphWeights read_signed_morph_weights(const std::string& read_path, std::vector<std::string>& warnings);

}  // namespace OpenMeshSkinned::detail
