#pragma once
/** \file GltfAccessors.hh
 *  A glTF accessor's values read as the spec gives them and written back as plain floats: the decoders of
 *  GltfDecompress.hh read quantised and sparse data and rewrite accessors in place. Internal to the importer.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

/// Bytes of one component of glTF component type \p type (0 for an unknown type).
size_t component_size(int type);
/// Components of one element of accessor type \p type ("VEC3": 3; 0 for an unknown type).
size_t component_count(const std::string& type);
/// One component as the spec reads it: normalised integers map to [0, 1] or [-1, 1].
double read_component(const char* p, int type, bool normalized);

/// Whether \p count elements of \p elem bytes, \p step apart from byte \p start, lie within \p size bytes;
/// in elements, so that no product of numbers from the file can overflow.
bool fits(size_t start, size_t count, size_t step, size_t elem, size_t size);

/** Every value of accessor \p a as the spec gives it (or, \p as_stored, as integers before normalisation),
 *  sparse substitutions included, components of an element next to each other. Throws IOError, naming
 *  \p shown_as and the accessor, for an unknown type or data that runs past its buffer views. */
std::vector<double> accessor_values(nlohmann::json& doc, size_t a, GltfBytes& bytes, const std::string& shown_as,
                                    bool as_stored = false);

/// Points accessor \p accessor at the whole of buffer view \p view: \p count elements of \p component_type, not sparse.
void point_accessor_at(nlohmann::json& accessor, size_t view, int component_type, size_t count);

/// Rewrites accessor \p a as floats holding \p values (in a new buffer view), its bounds recomputed when it had any.
void write_float_accessor(nlohmann::json& doc, size_t a, const std::vector<double>& values, GltfBytes& bytes);

}  // namespace OpenMeshSkinned::detail
