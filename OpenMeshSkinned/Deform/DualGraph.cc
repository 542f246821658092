#include "OpenMeshSkinned/Deform/DualGraph.hh"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace OpenMeshSkinned::detail {

DualGraph dual_graph(const SkinnedMesh& mesh, const FramePoints& ref, const FaceGradients<SkinnedMesh>& g,
                     double delta) {
  const std::vector<double> D = deformation_distances(mesh, ref, g, true);
  std::vector<double> geod(mesh.n_edges(), 0.0);  // centroid distance across each interior edge
  double sum_geod = 0.0;
  std::vector<double> interior;
  for (auto eh : mesh.edges())
    if (!mesh.is_boundary(eh)) {
      geod[eh.idx()] = centroid_distance(mesh, ref, mesh.face_handle(mesh.halfedge_handle(eh, 0)),
                                         mesh.face_handle(mesh.halfedge_handle(eh, 1)));
      sum_geod += geod[eh.idx()];
      interior.push_back(D[eh.idx()]);
    }
  const size_t n = interior.size();
  const double avg_geod = n && sum_geod > 0.0 ? sum_geod / n : 1.0;
  // avg(D) of eq. 5 with the largest 1 % clipped: a few slivers, whose gradients blow up (a vertex
  // quantised onto its neighbour's line in some frame), would otherwise make the average hundreds of times
  // the typical distance and every other edge look rigid.
  double avg_d = 0.0;
  if (n) {
    std::vector<double> sorted = interior;
    const size_t k = std::min(n - 1, size_t(0.99 * double(n)));
    std::nth_element(sorted.begin(), sorted.begin() + long(k), sorted.end());
    const double clip = sorted[k];
    for (double x : interior) avg_d += std::min(x, clip) / double(n);
  }
  DualGraph G;
  G.arcs.resize(mesh.n_faces());
  G.area.assign(mesh.n_faces(), 0.0);
  for (auto fh : mesh.faces()) {
    auto fv = mesh.cfv_iter(fh);
    const Eigen::Vector3d& a = ref[(fv++)->idx()];
    const Eigen::Vector3d& b = ref[(fv++)->idx()];
    const Eigen::Vector3d& c = ref[fv->idx()];
    G.area[fh.idx()] = 0.5 * (b - a).cross(c - a).norm();
  }
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh)) continue;
    const auto fa = mesh.face_handle(mesh.halfedge_handle(eh, 0)), fb = mesh.face_handle(mesh.halfedge_handle(eh, 1));
    const double d_norm = avg_d > 0.0 ? D[eh.idx()] / avg_d : 0.0;
    const double dis = delta * geod[eh.idx()] / avg_geod + (1.0 - delta) * d_norm;
    const auto heh = mesh.halfedge_handle(eh, 0);
    const double edge = (ref[mesh.to_vertex_handle(heh).idx()] - ref[mesh.from_vertex_handle(heh).idx()]).norm();
    G.arcs[fa.idx()].push_back({fb.idx(), dis, d_norm, edge});
    G.arcs[fb.idx()].push_back({fa.idx(), dis, d_norm, edge});
  }
  return G;
}

std::vector<double> shortest_paths(const DualGraph& G, const std::vector<int>& sources, std::vector<int>* origin) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(G.arcs.size(), inf);
  if (origin) origin->assign(G.arcs.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (int s : sources) {
    dist[s] = 0.0;
    if (origin) (*origin)[s] = s;
    q.push({0.0, s});
  }
  while (!q.empty()) {
    const auto [d, f] = q.top();
    q.pop();
    if (d > dist[f]) continue;
    for (const Arc& a : G.arcs[f])
      if (d + a.dis < dist[a.to]) {
        dist[a.to] = d + a.dis;
        if (origin) (*origin)[a.to] = (*origin)[f];
        q.push({dist[a.to], a.to});
      }
  }
  return dist;
}

std::vector<int> influence_region(const DualGraph& G, const std::vector<char>& in_a, int p) {
  std::vector<int> comp = {p}, index(G.arcs.size(), -1);
  index[p] = 0;
  bool touches_a = false;
  for (size_t i = 0; i < comp.size(); ++i)
    for (const Arc& a : G.arcs[comp[i]]) {
      if (in_a[a.to])
        touches_a = true;
      else if (index[a.to] < 0)
        index[a.to] = int(comp.size()), comp.push_back(a.to);
    }
  if (!touches_a || comp.size() == 1) return comp;
  const long n = long(comp.size()) - 1;  // unknowns: comp without p
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (size_t i = 1; i < comp.size(); ++i) {
    double diag = 0.0;
    for (const Arc& a : G.arcs[comp[i]]) {
      const double w = 1.0 / std::max(a.dis, 1e-12);
      diag += w;
      if (a.to == p)
        rhs[long(i - 1)] += w;
      else if (!in_a[a.to])
        t.emplace_back(long(i - 1), index[a.to] - 1, -w);
    }
    t.emplace_back(long(i - 1), long(i - 1), diag);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  const Eigen::VectorXd u = solver.solve(rhs);
  std::vector<int> region = {p};
  for (size_t i = 1; i < comp.size(); ++i)
    if (solver.info() != Eigen::Success || u[long(i - 1)] >= 0.01) region.push_back(comp[i]);
  return region;
}

std::vector<std::vector<int>> pieces(const DualGraph& G, const std::vector<int>& part, int label) {
  std::vector<std::vector<int>> out;
  std::vector<char> seen(part.size(), 0);
  for (size_t f = 0; f < part.size(); ++f) {
    if (part[f] != label || seen[f]) continue;
    out.emplace_back(1, int(f));
    seen[f] = 1;
    for (size_t i = 0; i < out.back().size(); ++i)
      for (const Arc& a : G.arcs[out.back()[i]])
        if (part[a.to] == label && !seen[a.to]) seen[a.to] = 1, out.back().push_back(a.to);
  }
  return out;
}

}  // namespace OpenMeshSkinned::detail
