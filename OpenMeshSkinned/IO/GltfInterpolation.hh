#pragma once
/** \file GltfInterpolation.hh
 *  glTF animation samplers that assimp 5.2 reads wrongly, rewritten as LINEAR samplers that pose the same,
 *  before it reads them: it interpolates STEP keys linearly (a switch becomes a slow blend) and keeps only
 *  the values of CUBICSPLINE keys (their tangents, the curve between the keys, are lost). The tool writes
 *  LINEAR samplers, so the motion is kept, not the interpolation's name. Internal to GltfRepair.
 */

#include "OpenMeshSkinned/IO/GltfBytes.hh"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace OpenMeshSkinned::detail {

/// How long before each STEP key its LINEAR stand-in moves from the previous value to the key's, in seconds
/// (half the gap to the previous key when that is shorter).
constexpr double kStepRampSeconds = 1e-3;
/// LINEAR keys per CUBICSPLINE interval: the curve sampled at equal steps (its chords deviate from it by
/// 1/64 of what a single chord per interval would).
constexpr int kCubicSegments = 8;

/** Rewrites every STEP and CUBICSPLINE sampler of \p doc's animations as a LINEAR sampler on new float
 *  accessors (added through \p bytes): STEP as a ramp of kStepRampSeconds before each key, CUBICSPLINE as
 *  the spec's Hermite curve at kCubicSegments keys per interval (rotations normalised). Returns one line per
 *  rewritten kind for the user ("3 STEP samplers: ..."), empty when there was none. Throws IOError, naming
 *  \p shown_as and the sampler, when a sampler's output does not hold a whole number of values per key or a
 *  key's time or value is not finite (naming the key as the file numbers it). */
std::vector<std::string> linearize_samplers(nlohmann::json& doc, GltfBytes& bytes, const std::string& shown_as);

}  // namespace OpenMeshSkinned::detail
