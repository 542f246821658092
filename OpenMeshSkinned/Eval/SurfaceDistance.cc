#include "OpenMeshSkinned/Eval/SurfaceDistance.hh"

#include "OpenMeshSkinned/Eval/TriangleBvh.hh"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace OpenMeshSkinned {
namespace {

// Samples of \p from: its vertices, then n points by area (uniform in each triangle), with the triangle each
// of those lies on in \p source.
std::vector<Eigen::Vector3d> draw_samples(const TriangleSoup& from, size_t n, std::mt19937_64& rng, size_t& vertices,
                                          std::vector<int>& source) {
  source.clear();
  std::vector<Eigen::Vector3d> pts;
  std::vector<char> used(from.points.size(), 0);
  for (const auto& f : from.triangles)
    for (int i : f) used[i] = 1;
  for (size_t i = 0; i < from.points.size(); ++i)
    if (used[i]) pts.push_back(from.points[i]);
  vertices = pts.size();
  if (n == 0) return pts;  // a surface only searched (the final fit's): its areas would go unused
  std::vector<double> cum;
  double total = 0.0;
  for (const auto& f : from.triangles) {
    total += 0.5 * (from.points[f[1]] - from.points[f[0]]).cross(from.points[f[2]] - from.points[f[0]]).norm();
    cum.push_back(total);
  }
  if (total <= 0.0) return pts;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (size_t s = 0; s < n; ++s) {
    const size_t t =
        std::min(cum.size() - 1, size_t(std::lower_bound(cum.begin(), cum.end(), u(rng) * total) - cum.begin()));
    double r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1.0) {
      r1 = 1.0 - r1;
      r2 = 1.0 - r2;
    }
    const auto& f = from.triangles[t];
    const Eigen::Vector3d p =
        from.points[f[0]] + r1 * (from.points[f[1]] - from.points[f[0]]) + r2 * (from.points[f[2]] - from.points[f[0]]);
    pts.push_back(p);
    source.push_back(int(t));
  }
  return pts;
}

}  // namespace

struct MeasuredSurface::Impl {
  TriangleBvh bvh;
  std::vector<Eigen::Vector3d> samples;  // the vertices first, then the area samples
  size_t vertex_samples = 0;
  size_t area_samples = 0;
  uint64_t seed = 0;
  // The area samples in the leaf order of the triangles they lie on. Drawn at random, they jump across the
  // surface; measured in this order, consecutive queries reach into the same part of the other surface's
  // hierarchy, which stays in cache (bench/README.md, "The tool end to end against gltfpack").
  std::vector<uint32_t> area_order;
  // The vertex samples likewise, by the first triangle that uses each (the hierarchy's leaf order does
  // not change when it is posed again): a vertex with no hint of its own starts from the triangle the
  // vertex before it hit, which lies near its answer.
  std::vector<uint32_t> vertex_order;

  void order_vertices(const TriangleSoup& soup) {
    std::vector<int> first(soup.points.size(), -1);
    for (size_t t = soup.triangles.size(); t-- > 0;)
      for (int v : soup.triangles[t]) first[v] = int(t);
    std::vector<std::pair<int, uint32_t>> keyed;
    for (size_t i = 0; i < soup.points.size(); ++i)
      if (first[i] >= 0) keyed.emplace_back(bvh.rank(first[i]), uint32_t(keyed.size()));
    std::sort(keyed.begin(), keyed.end());
    vertex_order.resize(keyed.size());
    for (size_t k = 0; k < keyed.size(); ++k) vertex_order[k] = keyed[k].second;
  }

  void draw(const TriangleSoup& soup) {
    std::mt19937_64 rng(seed);
    std::vector<int> source;
    samples = draw_samples(soup, area_samples, rng, vertex_samples, source);
    std::vector<std::pair<int, uint32_t>> keyed(source.size());
    for (size_t k = 0; k < source.size(); ++k) keyed[k] = {bvh.rank(source[k]), uint32_t(k)};
    std::sort(keyed.begin(), keyed.end());
    area_order.resize(keyed.size());
    for (size_t k = 0; k < keyed.size(); ++k) area_order[k] = keyed[k].second;
  }
};

MeasuredSurface::MeasuredSurface(const TriangleSoup& soup, size_t n, uint64_t seed) : impl_(std::make_unique<Impl>()) {
  impl_->area_samples = n;
  impl_->seed = seed;
  impl_->bvh = TriangleBvh(soup);
  impl_->order_vertices(soup);
  impl_->draw(soup);
}

void MeasuredSurface::repose(const TriangleSoup& soup) {
  if (soup.triangles != impl_->bvh.triangles())
    throw std::invalid_argument("MeasuredSurface::repose: not the triangles it was built with");
  impl_->bvh.refit(soup.points);
  impl_->draw(soup);
}
MeasuredSurface::~MeasuredSurface() = default;

int MeasuredSurface::rank(int triangle) const { return impl_->bvh.rank(triangle); }

double MeasuredSurface::distance(const Eigen::Vector3d& p) const {
  int triangle = -1;
  return distance(p, triangle, -1);
}

double MeasuredSurface::distance(const Eigen::Vector3d& p, int& triangle) const { return distance(p, triangle, -1); }

double MeasuredSurface::distance(const Eigen::Vector3d& p, int& triangle, int hint) const {
  return std::sqrt(impl_->bvh.nearest(p, triangle, hint));
}

namespace {

// \p from's samples measured to \p to. With \p hints, each vertex's query starts from its hint's triangle
// where it has one, and the hint becomes the triangle found. With a \p stride above 1 only every stride-th
// vertex in leaf order (spread evenly over the surface) is measured for the sum, standing for the others; those
// can still raise the maximum, and the distance to their hint's triangle bounds theirs from above, so only
// those whose bound exceeds the maximum found so far are searched: the maximum every vertex would give.
void one_way(const MeasuredSurface::Impl& from, const MeasuredSurface::Impl& to, std::vector<int>* hints, size_t stride,
             double& sum_sq, double& max_d, size_t& count) {
  if (to.bvh.empty()) return;
  if (hints) hints->resize(from.vertex_samples, -1);
  auto add = [&](double d2) {
    sum_sq += d2;
    max_d = std::max(max_d, std::sqrt(d2));
    ++count;
  };
  // Searched in leaf order, each from its hint or else from the triangle the query before it hit, and summed
  // in the order of the samples: the same sum, to the last bit, as one loop over them without hints.
  int found = -1, previous = -1;
  std::vector<double> d2(from.vertex_samples);
  std::vector<uint32_t> bounded;  // vertices not counted, in leaf order
  double counted_sum = 0.0;       // with a stride: the counted vertices', in leaf order
  size_t n_counted = 0;
  for (size_t j = 0; j < from.vertex_order.size(); ++j) {
    const uint32_t k = from.vertex_order[j];
    const int hint = hints && (*hints)[k] >= 0 ? (*hints)[k] : previous;
    if (stride > 1 && j % stride != 0) {
      d2[k] = to.bvh.distance2_to(from.samples[k], hint);
      bounded.push_back(k);
      continue;
    }
    d2[k] = to.bvh.nearest(from.samples[k], found, hint);
    if (hints) (*hints)[k] = found;
    if (found >= 0) previous = found;
    if (stride > 1) {
      counted_sum += d2[k];
      max_d = std::max(max_d, std::sqrt(d2[k]));
      ++n_counted;
    }
  }
  if (stride <= 1) {
    for (double x : d2) add(x);
  } else if (n_counted > 0) {
    // The counted vertices stand for all of them, each for as many as were strided over: the RMS estimates
    // the one every vertex would give (the directions and the area samples keep their weights in the pool).
    sum_sq += counted_sum * double(d2.size()) / double(n_counted);
    count += d2.size();
  }
  const Eigen::Vector3d* area = from.samples.data() + from.vertex_samples;
  std::vector<double> a2(from.area_order.size(), 0.0);
  for (uint32_t k : from.area_order) {
    a2[k] = to.bvh.nearest(area[k], found, previous);
    if (found >= 0) previous = found;
  }
  for (double x : a2) add(x);
  for (uint32_t k : bounded) {
    if (!(std::sqrt(d2[k]) > max_d)) continue;
    const int hint = hints && (*hints)[k] >= 0 ? (*hints)[k] : previous;
    max_d = std::max(max_d, std::sqrt(to.bvh.nearest(from.samples[k], found, hint)));
    if (hints) (*hints)[k] = found;
    if (found >= 0) previous = found;
  }
}

// Every stride-th vertex of \p from counts when it has more than \p counted vertices (0: all count).
size_t vertex_stride(const MeasuredSurface::Impl& from, size_t counted) {
  return counted > 0 && from.vertex_samples > counted ? (from.vertex_samples + counted - 1) / counted : 1;
}

SurfaceDistance pooled(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>* a_hints,
                       std::vector<int>* b_hints, size_t counted_vertices) {
  double sum_sq = 0.0, max_d = 0.0;
  size_t count = 0;
  one_way(a.impl(), b.impl(), a_hints, vertex_stride(a.impl(), counted_vertices), sum_sq, max_d, count);
  one_way(b.impl(), a.impl(), b_hints, vertex_stride(b.impl(), counted_vertices), sum_sq, max_d, count);
  SurfaceDistance d;
  d.samples = count;
  d.rms = count ? std::sqrt(sum_sq / count) : 0.0;
  d.hausdorff = max_d;
  return d;
}

}  // namespace

const MeasuredSurface& posed_surface(std::unique_ptr<MeasuredSurface>& slot, const TriangleSoup& soup, size_t samples,
                                     uint64_t seed) {
  if (slot)
    slot->repose(soup);
  else
    slot = std::make_unique<MeasuredSurface>(soup, samples, seed);
  return *slot;
}

MeasuredSurface::MeasuredSurface(MeasuredSurface&&) noexcept = default;
MeasuredSurface& MeasuredSurface::operator=(MeasuredSurface&&) noexcept = default;

SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>& a_hints,
                                 std::vector<int>& b_hints, size_t counted_vertices) {
  return pooled(a, b, &a_hints, &b_hints, counted_vertices);
}

SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b) {
  return pooled(a, b, nullptr, nullptr, 0);
}

SurfaceDistance surface_distance(const TriangleSoup& a, const TriangleSoup& b, size_t n, uint64_t seed) {
  // Each surface its own stream, so that a surface measured against many keeps the same samples.
  return surface_distance(MeasuredSurface(a, n, seed), MeasuredSurface(b, n, seed + 0x9E3779B97F4A7C15ull));
}

}  // namespace OpenMeshSkinned
