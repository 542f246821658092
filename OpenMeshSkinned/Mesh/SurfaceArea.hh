#pragma once
/** \file SurfaceArea.hh
 *  The rest pose's surface area: what ModSkinnedQuadricT::set_area_floor is measured against (the tool's
 *  floor is a few of the coarsest level's mean triangles, surface_area(mesh) / faces each).
 */

namespace OpenMeshSkinned {

/// The summed area of \p mesh's live faces at their points, each face fanned from its first vertex.
template <typename MeshT>
double surface_area(const MeshT& mesh) {
  double area = 0.0;
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const auto p0 = mesh.point(*fv);
    auto prev = mesh.point(*++fv);
    for (++fv; fv.is_valid(); ++fv) {
      const auto p = mesh.point(*fv);
      area += 0.5 * double(((prev - p0) % (p - p0)).norm());
      prev = p;
    }
  }
  return area;
}

}  // namespace OpenMeshSkinned
