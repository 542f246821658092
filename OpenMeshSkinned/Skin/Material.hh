#pragma once
/** \file Material.hh
 *  A material and its base-colour texture as they came in, carried to the exported LODs.
 */

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// An image a material uses, carried as encoded bytes so that every output can embed it.
struct Image {
  std::string name;                 ///< where it came from (a file name, or the embedded texture's name)
  std::string mime_type;            ///< "image/png" or "image/jpeg" (the two glTF 2.0 allows)
  std::vector<unsigned char> data;  ///< the encoded file
};

/// A material as it came in, kept so that the exported LODs look like the input.
struct Material {
  std::string name;
  double base_color[4] = {1.0, 1.0, 1.0, 1.0};
  std::string base_color_texture;  ///< the path or name as stored in the source; empty when none
  Image base_color_image;          ///< the texture's bytes; empty when it could not be found or read
};

}  // namespace OpenMeshSkinned
