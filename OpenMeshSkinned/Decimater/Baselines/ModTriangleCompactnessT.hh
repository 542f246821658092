#pragma once
/** \file ModTriangleCompactnessT.hh */

#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"
#include "OpenMeshSkinned/Solver/WeightRules.hh"

#include <cmath>

namespace OpenMeshSkinned {

/** Priority module: Savoye & Meyer's mesh LoD (2008, 4.2.3), a baseline. Triangles go in order of their
 *  compactness 4 sqrt(3) a / (l1^2 + l2^2 + l3^2) (1 for an equilateral triangle, 0 for a sliver), the
 *  least compact first; the merged vertex goes to the triangle's barycentre and its skin is made by Power
 *  Skinning (WeightRule::PowerSkinning). Priority units: compactness, dimensionless in [0, 1].
 *
 *  The paper collapses a whole triangle (its three vertices into one, four triangles gone). OpenMesh
 *  decimates by halfedge collapses, so a triangle collapse is two of them in a row: an edge a-b is priced
 *  by the less compact of its two triangles, and collapsing it merges a and b at that triangle's
 *  barycentre, which removes the triangle and its neighbour across the edge; the third vertex c is then
 *  one edge away from the merged vertex, and that edge's triangles, now less compact still, follow. The
 *  price looks at the faces around the edge, so a collapse re-prices the whole ring of the surviving vertex
 *  (ring_dependent(), prices_by_endpoints() false).
 *
 *  \code
 *  OpenMeshSkinned::ModTriangleCompactnessT<Mesh>::Handle ht;
 *  dec.add(ht);
 *  \endcode
 */
template <typename MeshT>
class ModTriangleCompactnessT : public SolverModuleT<MeshT>, private EdgeModelT<MeshT> {
  using ModBase = OpenMesh::Decimater::ModBaseT<MeshT>;

public:
  DECIMATING_MODULE(ModTriangleCompactnessT, MeshT, TriangleCompactness);

  explicit ModTriangleCompactnessT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, false) { this->settings_changed(); }

  /// 4 sqrt(3) area / (sum of squared edge lengths) of the triangle \p a \p b \p c.
  static double compactness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double l = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    return l > 0.0 ? 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / l : 0.0;
  }

  bool prices_by_endpoints() const override { return false; }
  /// The merged vertex is placed by the solve, whichever endpoint survives (EdgePriority).
  bool prices_edges() const override { return true; }

protected:
  float price(const CollapseInfo& ci) override {
    const CollapseResult& r = this->solver().solve(ci);
    if (!r.valid) return float(ModBase::ILLEGAL_COLLAPSE);
    this->solver().note_legal_priority(ci, r.error);
    return static_cast<float>(r.error);
  }
  void contribute(SolverSettings& s) const override { s.placement = true; }
  EdgeModelT<MeshT>* edge_model() override { return this; }

private:
  bool ring_dependent() const override { return true; }

  void solve_edge(typename MeshT::VertexHandle a, typename MeshT::VertexHandle b, CollapseResult& out) override {
    const MeshT& mesh = ModBase::mesh();
    out.valid = false;
    const auto h = mesh.find_halfedge(a, b);
    if (!h.is_valid()) return;
    double worst = 2.0;
    for (auto hh : {h, mesh.opposite_halfedge_handle(h)}) {
      const auto f = mesh.face_handle(hh);
      if (!f.is_valid()) continue;
      Eigen::Vector3d p[3];
      int k = 0;
      for (auto v : mesh.fv_range(f)) p[k++] = to_eigen(mesh.point(v));
      const double c = compactness(p[0], p[1], p[2]);
      if (c < worst) {
        worst = c;
        out.position = (p[0] + p[1] + p[2]) / 3.0;
      }
    }
    if (worst > 1.5) return;  // no face: an isolated edge
    const auto h_inf = influences_handle(mesh);
    const Eigen::Vector3d pa = to_eigen(mesh.point(a)), pb = to_eigen(mesh.point(b));
    out.error = worst;
    out.weights = merge_weights(WeightRule::PowerSkinning, out.position, pa, mesh.property(h_inf, a), pb,
                                mesh.property(h_inf, b), this->solver().max_influences());
    out.valid = out.position.allFinite();
  }
};

}  // namespace OpenMeshSkinned
