#pragma once
/** \file Textures.hh
 *  Finding and reading the images a source file's materials name, so every LOD can carry them inside
 *  itself. glTF 2.0 allows PNG and JPEG only: other formats (TGA, BMP, PSD, GIF, ...) are decoded and
 *  re-encoded as PNG.
 */

#include "OpenMeshSkinned/Skin/Material.hh"

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/** The image format glTF names for \p bytes, from their first bytes: "image/png", "image/jpeg",
 *  "image/ktx2" (KHR_texture_basisu), "image/webp" (EXT_texture_webp); "" for any other. */
std::string gltf_mime_type(const std::vector<unsigned char>& bytes);

/** Why the PNG or JPEG \p bytes is cut short ("" when it is whole, or another format): a PNG must end its
 *  chunks with IEND, a JPEG hold its end-of-image marker. The glTF validator refuses a file carrying a
 *  truncated image, and a viewer shows garbage. */
std::string image_stream_problem(const std::vector<unsigned char>& bytes);

/** Decodes \p image (any format stb_image reads) into 8-bit RGBA texels; false when it cannot. */
bool decode_rgba(const Image& image, std::vector<unsigned char>& rgba, int& width, int& height);

/** Makes a glTF-ready image from an encoded file's bytes: whole PNG and JPEG files are kept as they are,
 *  any other format stb_image reads is re-encoded as PNG. Returns false and says why in \p problem
 *  otherwise (a truncated PNG or JPEG among them). */
bool encode_for_gltf(const std::vector<unsigned char>& bytes, const std::string& name, Image& out,
                     std::string& problem);

/** Makes a PNG from raw 8-bit RGBA texels (row-major, \p width x \p height). */
bool encode_rgba_png(const unsigned char* rgba, int width, int height, const std::string& name, Image& out);

/** Reads the image a material names as \p stored (as the source stored it: relative, absolute, with
 *  Windows separators or a drive letter) for a source file in \p source_dir: the path as it is when it
 *  exists (relative ones against \p source_dir), otherwise the file's base name in \p source_dir.
 *  Returns false and says why in \p problem when no readable image is found. */
bool read_texture_file(const std::string& stored, const std::string& source_dir, Image& out, std::string& problem);

/** Finds the file read_texture_file() reads and returns its bytes as they are in \p bytes and its base
 *  name in \p name. */
bool find_texture_file(const std::string& stored, const std::string& source_dir, std::vector<unsigned char>& bytes,
                       std::string& name, std::string& problem);

}  // namespace OpenMeshSkinned
