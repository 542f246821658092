#include "OpenMeshSkinned/Eval/SurfaceDistance.hh"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace OpenMeshSkinned {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Triangle = K::Triangle_3;
using Point = K::Point_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

std::vector<Triangle> to_cgal(const TriangleSoup& s) {
  std::vector<Triangle> t;
  t.reserve(s.triangles.size());
  for (const auto& f : s.triangles) {
    const auto& a = s.points[f[0]];
    const auto& b = s.points[f[1]];
    const auto& c = s.points[f[2]];
    t.emplace_back(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z()), Point(c.x(), c.y(), c.z()));
  }
  return t;
}

// Samples of \p from: its vertices, then n points by area (uniform in each triangle).
std::vector<Point> samples(const TriangleSoup& from, size_t n, std::mt19937_64& rng, size_t& vertices) {
  std::vector<Point> pts;
  std::vector<char> used(from.points.size(), 0);
  for (const auto& f : from.triangles)
    for (int i : f) used[i] = 1;
  for (size_t i = 0; i < from.points.size(); ++i)
    if (used[i]) pts.emplace_back(from.points[i].x(), from.points[i].y(), from.points[i].z());
  vertices = pts.size();
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
    pts.emplace_back(p.x(), p.y(), p.z());
  }
  return pts;
}

}  // namespace

struct MeasuredSurface::Impl {
  std::vector<Triangle> triangles;
  std::unique_ptr<Tree> tree;  // null for a surface without triangles
  std::vector<Point> samples;  // the vertices first, then the area samples
  size_t vertex_samples = 0;
};

MeasuredSurface::MeasuredSurface(const TriangleSoup& soup, size_t n, uint64_t seed, size_t hint_points)
    : impl_(std::make_unique<Impl>()) {
  std::mt19937_64 rng(seed);
  impl_->samples = samples(soup, n, rng, impl_->vertex_samples);
  impl_->triangles = to_cgal(soup);
  if (impl_->triangles.empty()) return;
  impl_->tree = std::make_unique<Tree>(impl_->triangles.begin(), impl_->triangles.end());
  const size_t nt = impl_->triangles.size();
  if (hint_points >= nt) {
    impl_->tree->accelerate_distance_queries();
  } else if (hint_points == 0) {
    impl_->tree->do_not_accelerate_distance_queries();  // else CGAL builds the full tree at the first query
  } else {
    const size_t stride = (nt + hint_points - 1) / hint_points;
    std::vector<Tree::Point_and_primitive_id> hints;
    hints.reserve(nt / stride + 1);
    for (size_t i = 0; i < nt; i += stride) {
      const Iterator it = impl_->triangles.begin() + i;
      hints.emplace_back(it->vertex(0), it);
    }
    impl_->tree->accelerate_distance_queries(hints.begin(), hints.end());
  }
}
MeasuredSurface::~MeasuredSurface() = default;

double MeasuredSurface::distance(const Eigen::Vector3d& p) const {
  if (!impl_->tree) return HUGE_VAL;
  return std::sqrt(impl_->tree->squared_distance(Point(p.x(), p.y(), p.z())));
}

double MeasuredSurface::distance(const Eigen::Vector3d& p, int& triangle) const { return distance(p, triangle, -1); }

namespace {

// The nearest point of \p s (which has a tree) to \p q, searched from triangle \p hint when it is one of
// \p s's (else from the tree's own start points); \p triangle gets the triangle it lies on.
Point nearest_on(const MeasuredSurface::Impl& s, const Point& q, int hint, int& triangle) {
  const bool hinted = hint >= 0 && hint < static_cast<int>(s.triangles.size());
  const Iterator h = s.triangles.begin() + (hinted ? hint : 0);
  const auto [nearest, it] =
      hinted ? s.tree->closest_point_and_primitive(q, {K().construct_projected_point_3_object()(*h, q), h})
             : s.tree->closest_point_and_primitive(q);
  triangle = static_cast<int>(it - s.triangles.begin());
  return nearest;
}

// \p from's samples measured to \p to. With \p hints, each vertex's query starts from its hint's triangle
// where it has one, and the hint becomes the triangle found.
void one_way(const MeasuredSurface::Impl& from, const MeasuredSurface::Impl& to, std::vector<int>* hints,
             double& sum_sq, double& max_d, size_t& count) {
  if (!to.tree) return;
  if (hints) hints->resize(from.vertex_samples, -1);
  for (size_t k = 0; k < from.samples.size(); ++k) {
    const Point& p = from.samples[k];
    double d2;
    if (hints) {
      int found = -1;
      d2 = CGAL::squared_distance(p, nearest_on(to, p, k < hints->size() ? (*hints)[k] : -1, found));
      if (k < hints->size()) (*hints)[k] = found;
    } else {
      d2 = to.tree->squared_distance(p);
    }
    sum_sq += d2;
    max_d = std::max(max_d, std::sqrt(d2));
    ++count;
  }
}

SurfaceDistance pooled(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>* a_hints,
                       std::vector<int>* b_hints) {
  double sum_sq = 0.0, max_d = 0.0;
  size_t count = 0;
  one_way(a.impl(), b.impl(), a_hints, sum_sq, max_d, count);
  one_way(b.impl(), a.impl(), b_hints, sum_sq, max_d, count);
  SurfaceDistance d;
  d.samples = count;
  d.rms = count ? std::sqrt(sum_sq / count) : 0.0;
  d.hausdorff = max_d;
  return d;
}

}  // namespace

double MeasuredSurface::distance(const Eigen::Vector3d& p, int& triangle, int hint) const {
  triangle = -1;
  if (!impl_->tree) return HUGE_VAL;
  const Point q(p.x(), p.y(), p.z());
  return std::sqrt(CGAL::squared_distance(q, nearest_on(*impl_, q, hint, triangle)));
}
MeasuredSurface::MeasuredSurface(MeasuredSurface&&) noexcept = default;
MeasuredSurface& MeasuredSurface::operator=(MeasuredSurface&&) noexcept = default;

SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b, std::vector<int>& a_hints,
                                 std::vector<int>& b_hints) {
  return pooled(a, b, &a_hints, &b_hints);
}

SurfaceDistance surface_distance(const MeasuredSurface& a, const MeasuredSurface& b) {
  return pooled(a, b, nullptr, nullptr);
}

SurfaceDistance surface_distance(const TriangleSoup& a, const TriangleSoup& b, size_t n, uint64_t seed) {
  // Each surface its own stream, so that a surface measured against many keeps the same samples.
  return surface_distance(MeasuredSurface(a, n, seed), MeasuredSurface(b, n, seed + 0x9E3779B97F4A7C15ull));
}

}  // namespace OpenMeshSkinned
