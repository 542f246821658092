#include "SwitchHints.hh"

#include <algorithm>
#include <limits>

namespace OpenMeshSkinned {

LodSwitchHint switch_hint(const SkinnedMesh& original, double hausdorff_percent, int screen_height) {
  SkinnedMesh::Point lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (auto vh : original.vertices()) {
    lo.minimize(original.point(vh));
    hi.maximize(original.point(vh));
  }
  LodSwitchHint h;
  if (original.n_vertices() == 0) return h;
  const auto size = hi - lo;
  const double diagonal = size.norm();
  const double largest = std::max({size[0], size[1], size[2]});
  const double error = hausdorff_percent / 100.0 * diagonal;
  if (!(error > 0.0)) return h;  // no visible error at any size
  h.unity_relative_height = std::min(1.0, largest / (error * screen_height));
  h.unreal_screen_size = std::min(1.0, diagonal / (error * screen_height));
  return h;
}

}  // namespace OpenMeshSkinned
