#pragma once
/** \file AreaPrice.hh
 *  A collapse's price from its error and the area it stands for, shared by the modules that offer
 *  set_area_exponent() and set_area_floor() (ModSkinnedQuadricT, ModFrameQuadricT).
 */

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

namespace OpenMeshSkinned {

/** \p error / \p area^\p exponent, except below \p floor, where it is \p error / \p area times
 *  floor^(1 - exponent): per area, scaled to meet the other price at the floor. An exponent of 0 is the
 *  error itself, 1 a mean squared distance; a collapse standing for no area is free (the planes of a
 *  degenerate neighbourhood see nothing it moves). */
inline double area_price(double error, double area, double exponent, double floor) {
  if (exponent == 0.0) return error;
  if (!(area > 0.0)) return 0.0;
  if (exponent == 1.0) return error / area;
  return error / area * std::pow(std::max(area, floor), 1.0 - exponent);
}

/// Throws std::invalid_argument, naming \p who, unless \p a is in [0, 1].
inline void check_area_exponent(const char* who, double a) {
  if (!(a >= 0.0 && a <= 1.0))
    throw std::invalid_argument(std::string(who) + ": the area exponent must be in [0, 1], not " + std::to_string(a));
}

/// Throws std::invalid_argument, naming \p who, unless \p A is finite and not negative.
inline void check_area_floor(const char* who, double A) {
  if (!(A >= 0.0 && A <= DBL_MAX))
    throw std::invalid_argument(std::string(who) + ": the area floor must be finite and not negative, not " +
                                std::to_string(A));
}

}  // namespace OpenMeshSkinned
