#pragma once
/** \file Material.hh
 *  A material and its textures as they came in, carried to the exported LODs: the glTF material object
 *  itself (from a glTF input as the file has it, from other formats mapped to glTF PBR on the way in).
 */

#include <memory>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// An image a material uses, carried as encoded bytes so that every output can embed it.
struct Image {
  std::string name;       ///< where it came from (a file name, or the embedded texture's name)
  std::string mime_type;  ///< "image/png", "image/jpeg", or (glTF inputs, kept as they are) "image/ktx2", "image/webp"
  std::vector<unsigned char> data;  ///< the encoded file
};

/// A glTF texture as a material uses it.
struct Texture {
  /// The glTF texture object as JSON, without "sampler": its "source" and every extension's "source"
  /// (KHR_texture_basisu, EXT_texture_webp) index \ref images.
  std::string gltf = "{}";
  std::string sampler;  ///< the glTF sampler object as JSON; empty: none (repeat, the viewer's filters)
  /// Shared by every texture that shows the same image of the input (an atlas may serve many materials).
  std::vector<std::shared_ptr<const Image>> images;
};

/// A material as it came in, kept so that the exported LODs look like the input.
struct Material {
  std::string name;
  double base_color[4] = {1.0, 1.0, 1.0, 1.0};  ///< pbrMetallicRoughness.baseColorFactor
  std::string base_color_texture;  ///< the base-colour image's name as the source stores it; empty when none
  /** The rest of the glTF material object as JSON ("name" and "baseColorFactor" are the fields above):
   *  every texture reference's "index" indexes \ref textures. Empty for a plain material of the base
   *  colour alone (non-metallic), as generated meshes make them. */
  std::string gltf;
  std::vector<Texture> textures;
  /// Extensions the material or its textures use that the input listed as required (its
  /// extensionsRequired); the output requires them too.
  std::vector<std::string> required_extensions;
};

}  // namespace OpenMeshSkinned
