#pragma once
/** \file Validate.hh
 *  Checks that a mesh's skin is usable, and repairs what can be repaired without guessing.
 */

#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace OpenMeshSkinned {

/// A skin that cannot be used; what() names the first offending vertex and the problem.
class SkinError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct ValidationOptions {
  /// Weight sums within 1 +- this are rescaled to exactly 1; sums further off are rejected.
  double sum_tolerance = 1e-2;
  /// Largest number of influences a vertex may carry (at most Influences::kCapacity).
  int max_influences = Influences::kCapacity;
};

struct ValidationReport {
  size_t vertices_checked = 0;
  size_t vertices_renormalized = 0;  ///< sums were off by less than the tolerance
};

/** Validates every non-deleted vertex's influences against the skeleton; renormalises small deviations.
 *  Throws SkinError on non-finite or negative weights, sums beyond tolerance (including 0), joint
 *  indices out of range, vertices without influences, and more influences than allowed. */
template <typename Mesh>
ValidationReport validate_skin(Mesh& mesh, const ValidationOptions& opt = {}) {
  const auto h = influences_handle(mesh);
  const int n_joints = skeleton(mesh).size();
  ValidationReport rep;
  auto fail = [](size_t v, const std::string& what) { throw SkinError("vertex " + std::to_string(v) + ": " + what); };
  for (auto vh : mesh.vertices()) {
    Influences& inf = mesh.property(h, vh);
    const size_t v = vh.idx();
    ++rep.vertices_checked;
    if (inf.empty()) fail(v, "has no bone influences");
    if (inf.size() > opt.max_influences)
      fail(v, std::to_string(inf.size()) + " influences, more than the allowed " + std::to_string(opt.max_influences));
    for (const JointWeight& jw : inf) {
      if (!std::isfinite(jw.weight)) fail(v, "non-finite weight for joint " + std::to_string(jw.joint));
      if (jw.weight < 0.0)
        fail(v, "negative weight " + std::to_string(jw.weight) + " for joint " + std::to_string(jw.joint));
      if (jw.joint < 0 || jw.joint >= n_joints)
        fail(v, "joint index " + std::to_string(jw.joint) + " out of range (skeleton has " + std::to_string(n_joints) +
                    " joints)");
    }
    const double s = inf.sum();
    if (std::abs(s - 1.0) > opt.sum_tolerance) {
      std::ostringstream os;
      os << "weights sum to " << s << ", not 1 (tolerance " << opt.sum_tolerance << ")";
      fail(v, os.str());
    }
    if (s != 1.0) {
      inf.normalize();
      inf.sort();
      ++rep.vertices_renormalized;
    }
  }
  return rep;
}

}  // namespace OpenMeshSkinned
