#pragma once
/** \file MaterialImages.hh
 *  The images behind a material that assimp reports: where its texture comes from (embedded in the file or
 *  beside it, or guessed for a Quake model that names none), whether a "bump" map is really a normal map,
 *  and two maps packed into one image the way glTF wants them. Internal to the reader (ImportMaterial.cc).
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <functional>
#include <string>
#include <vector>

struct aiScene;

namespace OpenMeshSkinned {

/** The one image beside \p source whose name starts with the model's (faerie.md2: faerie2.bmp); empty when
 *  there is none or more than one. \p found lists every candidate, sorted. */
std::string image_named_after(const std::string& source, std::vector<std::string>& found);

/** The skin of a Quake model \p source that names none: image_named_after() read from \p source_dir, its
 *  name in \p guessed. False with \p problem set when there is no such image, several, or it cannot be read. */
bool guess_skin_image(const std::string& source, const std::string& source_dir, Image& out, std::string& guessed,
                      std::string& problem);

/** The image \p stored names: embedded in \p scene ("*N", or a file name FBX and GLB files carry inside
 *  themselves) before a file beside the source in \p source_dir. False with \p problem set when neither
 *  can be read. */
bool fetch_image(const aiScene* scene, const std::string& stored, const std::string& source_dir, Image& out,
                 std::string& problem);

/** Whether \p image's pixels are a tangent-space normal map's (mostly +Z: blue high, red and green near the
 *  middle) rather than a grey height map's. Some exporters (OBJ's bump, FBX's Bump) store normal maps as
 *  height maps. */
bool looks_like_normal_map(const Image& image);

/** Writes one output texel (RGBA) from the texels of both inputs at the same place, nullptr where an
 *  input is absent. */
using TexelPacker = std::function<void(unsigned char* out, const unsigned char* a, const unsigned char* b)>;

/** A new RGBA PNG as large as the larger of \p a and \p b (either may be null, not both), each texel
 *  written by \p texel; named after the first present input's name with "_packed.png". False when an input
 *  cannot be decoded. */
bool pack_images(const Image* a, const Image* b, Image& out, const TexelPacker& texel);

}  // namespace OpenMeshSkinned
