#include "OpenMeshSkinned/Solver/FitSamples.hh"

#include <algorithm>

namespace OpenMeshSkinned {

std::vector<std::array<int, 3>> mesh_triangles(const SkinnedMesh& mesh) {
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.n_faces());
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const int a = (fv++)->idx(), b = (fv++)->idx(), c = fv->idx();
    triangles.push_back({a, b, c});
  }
  return triangles;
}

std::vector<size_t> strided_samples(const SkinnedMesh& mesh, size_t n_triangles, size_t max_samples) {
  const size_t total = mesh.n_vertices() + n_triangles;
  const size_t stride = std::max<size_t>(1, (total + max_samples - 1) / std::max<size_t>(1, max_samples));
  std::vector<size_t> samples;
  for (size_t i = 0; i < total; i += stride)
    if (i >= mesh.n_vertices() || !mesh.status(SkinnedMesh::VertexHandle(int(i))).deleted()) samples.push_back(i);
  return samples;
}

}  // namespace OpenMeshSkinned
