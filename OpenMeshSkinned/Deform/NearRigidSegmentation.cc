#include "OpenMeshSkinned/Deform/NearRigidSegmentation.hh"

#include "OpenMeshSkinned/Deform/DualGraph.hh"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>

namespace OpenMeshSkinned {

namespace {

using detail::Arc;
using detail::dual_graph;
using detail::DualGraph;
using detail::influence_region;
using detail::pieces;
using detail::shortest_paths;

// Area-weighted average deformation gradient of \p faces, per frame (Lee 3.2: a region's deformation).
std::vector<Eigen::Matrix3d> average_gradient(const FaceGradients<SkinnedMesh>& g, const DualGraph& G,
                                              const std::vector<int>& faces, double* area_out) {
  std::vector<Eigen::Matrix3d> N(g.M.size(), Eigen::Matrix3d::Zero());
  double area = 0.0;
  for (int f : faces) {
    if (!g.valid[f]) continue;
    area += G.area[f];
    for (size_t t = 0; t < g.M.size(); ++t) N[t] += G.area[f] * g.M[t][f];
  }
  for (auto& m : N) m = area > 0.0 ? Eigen::Matrix3d(m / area) : Eigen::Matrix3d::Identity();
  if (area_out) *area_out = area;
  return N;
}

// 3.4: the boundary between two neighbouring parts re-cut by a minimum cut (Boykov-Kolmogorov max flow)
// through the band of faces within \p hops of it, the faces beyond the band tied to their side. The
// capacity of an edge between two faces follows eq. 8's ingredients, alpha weighting deformation and
// 1 - alpha the shared edge's length (short cuts are smooth); the extracted eq. 8 adds D/avg(D) itself,
// which would make the cut avoid the bending regions the prose says it passes through, so the deformation
// term here is Katz & Tal's 1 / (1 + D/avg(D)) (the paper's reference [15]). A re-cut that would split
// either part is not taken.
void smooth_boundaries(const DualGraph& G, std::vector<int>& part, double alpha, int hops) {
  using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
  using FlowGraph = boost::adjacency_list<
      boost::vecS, boost::vecS, boost::directedS,
      boost::property<
          boost::vertex_index_t, long,
          boost::property<boost::vertex_color_t, boost::default_color_type,
                          boost::property<boost::vertex_distance_t, long,
                                          boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>>,
      boost::property<boost::edge_capacity_t, double,
                      boost::property<boost::edge_residual_capacity_t, double,
                                      boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;
  const size_t nf = part.size();
  double sum_edge = 0.0;
  size_t n_edge = 0;
  std::set<std::pair<int, int>> pairs;
  for (size_t f = 0; f < nf; ++f)
    for (const Arc& a : G.arcs[f]) {
      sum_edge += a.edge, ++n_edge;
      if (part[f] < part[a.to]) pairs.insert({part[f], part[a.to]});
    }
  const double avg_edge = n_edge && sum_edge > 0.0 ? sum_edge / n_edge : 1.0;
  const double infinite = 1e30;
  for (const auto& [pa, pb] : pairs) {
    auto ours = [&](int f) { return part[f] == pa || part[f] == pb; };
    std::vector<int> hop(nf, -1), band;
    for (size_t f = 0; f < nf; ++f)
      if (ours(int(f)))
        for (const Arc& a : G.arcs[f])
          if (ours(a.to) && part[a.to] != part[f]) {
            hop[f] = 0;
            band.push_back(int(f));
            break;
          }
    for (size_t i = 0; i < band.size(); ++i)
      if (hop[band[i]] < hops)
        for (const Arc& a : G.arcs[band[i]])
          if (ours(a.to) && hop[a.to] < 0) hop[a.to] = hop[band[i]] + 1, band.push_back(a.to);
    std::vector<long> index(nf, -1);
    for (size_t i = 0; i < band.size(); ++i) index[band[i]] = long(i);
    FlowGraph g(band.size() + 2);
    const long s = long(band.size()), t = s + 1;
    auto cap = boost::get(boost::edge_capacity, g);
    auto rev = boost::get(boost::edge_reverse, g);
    auto link = [&](long u, long v, double c_uv, double c_vu) {
      const auto e = boost::add_edge(u, v, g).first, r = boost::add_edge(v, u, g).first;
      cap[e] = c_uv, cap[r] = c_vu, rev[e] = r, rev[r] = e;
    };
    bool to_source = false, to_sink = false;
    for (int f : band)
      for (const Arc& a : G.arcs[f]) {
        if (index[a.to] >= 0) {
          if (f < a.to) {
            const double c = alpha / (1.0 + a.d_norm) + (1.0 - alpha) * a.edge / avg_edge;
            link(index[f], index[a.to], c, c);
          }
        } else if (part[a.to] == pa) {
          link(s, index[f], infinite, 0.0), to_source = true;
        } else if (part[a.to] == pb) {
          link(index[f], t, infinite, 0.0), to_sink = true;
        }
      }
    if (!to_source || !to_sink) continue;
    boost::boykov_kolmogorov_max_flow(g, s, t);
    auto colour = boost::get(boost::vertex_color, g);
    std::vector<int> next = part;
    for (size_t i = 0; i < band.size(); ++i)
      next[band[i]] = boost::get(colour, long(i)) == boost::get(colour, s) ? pa : pb;
    if (pieces(G, next, pa).size() == 1 && pieces(G, next, pb).size() == 1) part = std::move(next);
  }
}

// Eq. 7: a face goes to the part i that minimises min(distance to i's nearest feature face, average
// distance to i's faces), repeated until no face moves (at most 10 rounds, as the paper reports). The
// average over all of F_i would take all-pairs shortest paths (the paper's own memory limit); it is taken
// over up to 24 faces of F_i spread through it (every k-th by index), fewer on large meshes so that a round
// costs at most about 4e7 face visits.
void refine_by_average_distance(const DualGraph& G, const std::vector<int>& features,
                                const std::vector<int>& feature_part, int n_parts, std::vector<int>& part) {
  const size_t nf = part.size();
  const size_t samples = std::clamp<size_t>(size_t(4e7 / double(std::max<size_t>(1, nf * size_t(n_parts)))), 1, 24);
  const double inf = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 10; ++round) {
    std::vector<double> best(nf, inf);
    std::vector<int> next(part);
    for (int i = 0; i < n_parts; ++i) {
      std::vector<int> mine, members;
      for (size_t k = 0; k < features.size(); ++k)
        if (feature_part[k] == i) mine.push_back(features[k]);
      for (size_t f = 0; f < nf; ++f)
        if (part[f] == i) members.push_back(int(f));
      if (mine.empty() || members.empty()) continue;
      const std::vector<double> to_feature = shortest_paths(G, mine);
      std::vector<double> average(nf, 0.0);
      const size_t m = std::min(samples, members.size());
      for (size_t j = 0; j < m; ++j) {
        const std::vector<double> d = shortest_paths(G, {members[j * members.size() / m]});
        for (size_t f = 0; f < nf; ++f) average[f] += d[f] / double(m);
      }
      for (size_t f = 0; f < nf; ++f) {
        const double c = std::min(to_feature[f], average[f]);
        if (c < best[f]) best[f] = c, next[f] = i;
      }
    }
    if (next == part) return;
    part = std::move(next);
  }
}

// 3.2: the feature faces, and the part each starts or joins.
struct Features {
  std::vector<int> faces;
  std::vector<int> part;
};

Features find_features(const FaceGradients<SkinnedMesh>& g, const DualGraph& G, const SegmentationSettings& s) {
  const size_t nf = G.arcs.size();
  double total_area = 0.0;
  for (double a : G.area) total_area += a;
  std::vector<char> in_a(nf, 0);
  for (size_t f = 0; f < nf; ++f)
    for (const Arc& a : G.arcs[f])
      if (a.dis > s.epsilon) in_a[f] = 1;
  Features out;
  std::vector<std::vector<Eigen::Matrix3d>> part_gradient;
  std::vector<double> part_area;
  // A region becomes a part of its own or joins the part whose deformation is within gamma of its own.
  auto add_region = [&](int p, const std::vector<int>& R) {
    double r_area = 0.0;
    const std::vector<Eigen::Matrix3d> N = average_gradient(g, G, R, &r_area);
    int join = -1;
    for (size_t k = 0; k < part_gradient.size() && join < 0; ++k) {
      double mean = 0.0;
      for (size_t t = 0; t < N.size(); ++t) mean += (N[t] - part_gradient[k][t]).squaredNorm() / N.size();
      if (mean <= s.gamma) join = int(k);
    }
    if (join < 0) {
      join = int(part_gradient.size());
      part_gradient.push_back(N);
      part_area.push_back(r_area);
    } else if (r_area > 0.0) {
      const double w = part_area[join] + r_area;
      for (size_t t = 0; t < N.size(); ++t)
        part_gradient[join][t] = (part_area[join] * part_gradient[join][t] + r_area * N[t]) / w;
      part_area[join] = w;
    }
    out.faces.push_back(p);
    out.part.push_back(join);
    for (int f : R) in_a[f] = 1;
  };
  // Pieces of the mesh where nothing bends (no face of A reaches them: a separate rigid accessory, or a
  // whole mesh that moves rigidly) are each one region, whatever their size.
  {
    std::vector<int> a_faces;
    for (size_t f = 0; f < nf; ++f)
      if (in_a[f]) a_faces.push_back(int(f));
    const std::vector<double> d = shortest_paths(G, a_faces);
    for (size_t f = 0; f < nf; ++f)
      if (!in_a[f] && std::isinf(d[f])) add_region(int(f), influence_region(G, in_a, int(f)));
  }
  for (size_t round = 0; round < nf; ++round) {
    std::vector<int> a_faces;
    for (size_t f = 0; f < nf; ++f)
      if (in_a[f]) a_faces.push_back(int(f));
    if (a_faces.size() == nf) break;
    const std::vector<double> d = shortest_paths(G, a_faces);
    int p = -1;
    double best = -1.0;
    for (size_t f = 0; f < nf; ++f)
      if (!in_a[f] && d[f] > best) best = d[f], p = int(f);
    const std::vector<int> R = influence_region(G, in_a, p);
    double area = 0.0;
    for (int f : R) area += G.area[f];
    if (area < s.min_region_area * total_area) break;
    add_region(p, R);
  }
  if (out.faces.empty()) {
    out.faces.push_back(0);
    out.part.push_back(0);
  }
  return out;
}

// A piece of part \p label that holds no feature face goes to the neighbouring part it shares the most
// edges with.
void absorb_piece(const DualGraph& G, const std::vector<int>& piece, int label, std::vector<int>& part) {
  std::map<int, int> votes;
  for (int f : piece)
    for (const Arc& a : G.arcs[f])
      if (part[a.to] != label && part[a.to] >= 0) ++votes[part[a.to]];
  if (votes.empty()) return;
  const int to =
      std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
  for (int f : piece) part[f] = to;
}

// 3.3: each face to the part of its nearest feature face (eq. 6), refined by eq. 7; a part in pieces is split
// (pieces with feature faces become parts of their own) or absorbed (pieces without).
std::vector<int> assign_parts(const DualGraph& G, Features& ft) {
  const size_t nf = G.arcs.size();
  std::vector<int> part(nf, 0);
  for (int iter = 0; iter < 10; ++iter) {
    std::vector<int> origin;
    shortest_paths(G, ft.faces, &origin);
    std::map<int, int> part_of_feature;
    for (size_t i = 0; i < ft.faces.size(); ++i) part_of_feature[ft.faces[i]] = ft.part[i];
    for (size_t f = 0; f < nf; ++f) part[f] = origin[f] < 0 ? -1 : part_of_feature[origin[f]];
    const int n_parts = *std::max_element(ft.part.begin(), ft.part.end()) + 1;
    refine_by_average_distance(G, ft.faces, ft.part, n_parts, part);
    bool split = false;
    for (int label = 0; label < n_parts; ++label) {
      bool first_with_features = true;
      for (const auto& piece : pieces(G, part, label)) {
        std::vector<size_t> features;
        for (size_t i = 0; i < ft.faces.size(); ++i)
          if (std::find(piece.begin(), piece.end(), ft.faces[i]) != piece.end()) features.push_back(i);
        if (features.empty()) {
          absorb_piece(G, piece, label, part);
        } else if (!first_with_features) {
          const int fresh = *std::max_element(ft.part.begin(), ft.part.end()) + 1;
          for (size_t i : features) ft.part[i] = fresh;
          split = true;
        } else {
          first_with_features = false;
        }
      }
    }
    if (!split) break;
  }
  return part;
}

}  // namespace

Segmentation segment_near_rigid(const SkinnedMesh& mesh, const FramePoints& ref, const std::vector<FramePoints>& frames,
                                const SegmentationSettings& s) {
  const FaceGradients<SkinnedMesh> g(mesh, ref, frames);
  const DualGraph G = dual_graph(mesh, ref, g, s.delta);
  Features ft = find_features(g, G, s);
  std::vector<int> part = assign_parts(G, ft);
  // Faces no feature face reaches (a piece of the mesh with none) form parts of their own.
  int fresh = -2;
  for (const auto& piece : pieces(G, part, -1)) {
    for (int x : piece) part[x] = fresh;
    --fresh;
  }
  smooth_boundaries(G, part, s.alpha, s.smoothing_hops);
  Segmentation out;
  out.feature_faces = ft.faces;
  // Labels in order of first appearance, so that equal segmentations compare equal.
  std::map<int, int> order;
  const size_t nf = mesh.n_faces();
  out.part.assign(nf, 0);
  for (size_t f = 0; f < nf; ++f) {
    if (!order.count(part[f])) order[part[f]] = int(order.size());
    out.part[f] = order[part[f]];
  }
  out.parts = int(order.size());
  return out;
}

}  // namespace OpenMeshSkinned
