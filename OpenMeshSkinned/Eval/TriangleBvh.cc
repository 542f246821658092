#include "OpenMeshSkinned/Eval/TriangleBvh.hh"

#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"

#include <Eigen/Geometry>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace OpenMeshSkinned {
namespace {

constexpr int kLeaf = 4;
// A box is passed over only when it is farther than the best by more than rounding could account for:
// the answer must be the least (distance, index) over every triangle, whatever the order of the search.
constexpr double kSlack = 1e-9;
constexpr double kMarginUlps = 16.0;
// The plane test's allowance for a unit normal kept in floats (each component within half a float ulp).
constexpr double kNormalUlps = 4.0;
// The least sine of a corner angle whose normal is trusted (its direction then holds to far below a float ulp).
constexpr double kMinSine = 1e-6;

// A triangle while the hierarchy is split: its box centre, in floats (the split only orders them; the
// boxes searched are computed from the triangles afterwards), and its index.
struct Item {
  float centre[3];
  int id;
};

}  // namespace

TriangleBvh::TriangleBvh(const TriangleSoup& soup) {
  const int n = static_cast<int>(soup.triangles.size());
  if (n == 0) return;
  // Centres relative to the soup's middle, so that floats still order them far from the origin.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (const auto& t : soup.triangles)
    for (int v : t) {
      if (v < 0 || size_t(v) >= soup.points.size()) throw std::out_of_range("TriangleBvh: a corner index out of range");
      max_index_ = std::max(max_index_, v);
      lo = lo.cwiseMin(soup.points[v]);
      hi = hi.cwiseMax(soup.points[v]);
    }
  const Eigen::Vector3d middle = (lo.array().isFinite() && hi.array().isFinite()).all()
                                     ? Eigen::Vector3d(0.5 * (lo + hi))
                                     : Eigen::Vector3d::Zero();
  std::vector<Item> items;
  items.reserve(n);
  for (int i = 0; i < n; ++i) {
    const auto& t = soup.triangles[i];
    const Eigen::Vector3d &a = soup.points[t[0]], &b = soup.points[t[1]], &c = soup.points[t[2]];
    const Eigen::Vector3d m = 0.5 * (a.cwiseMin(b).cwiseMin(c) + a.cwiseMax(b).cwiseMax(c)) - middle;
    Item item{{float(m.x()), float(m.y()), float(m.z())}, i};
    for (float& x : item.centre)
      if (std::isnan(x)) x = HUGE_VALF;  // the split's order must stay a strict weak order
    items.push_back(item);
  }
  nodes_.reserve(n);  // leaves hold 2 to kLeaf triangles (one for a one-triangle soup): at most n nodes
  nodes_.push_back(Node{});
  // Depth first, each node's children made right after it: a parent's index is below its children's.
  struct Range {
    int node, begin, end;
  };
  std::vector<Range> todo{{0, 0, n}};
  while (!todo.empty()) {
    const Range r = todo.back();
    todo.pop_back();
    if (r.end - r.begin <= kLeaf) {
      nodes_[r.node].first = r.begin;
      nodes_[r.node].count = r.end - r.begin;
      continue;
    }
    float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF}, hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
    for (int k = r.begin; k < r.end; ++k)
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], items[k].centre[i]);
        hi[i] = std::max(hi[i], items[k].centre[i]);
      }
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (hi[i] - lo[i] > hi[axis] - lo[axis]) axis = i;
    const int mid = r.begin + (r.end - r.begin) / 2;
    std::nth_element(items.begin() + r.begin, items.begin() + mid, items.begin() + r.end,
                     [axis](const Item& a, const Item& b) {
                       return a.centre[axis] < b.centre[axis] || (a.centre[axis] == b.centre[axis] && a.id < b.id);
                     });
    const int left = static_cast<int>(nodes_.size());
    nodes_[r.node].first = left;
    nodes_[r.node].count = 0;
    nodes_.push_back(Node{});
    nodes_.push_back(Node{});
    todo.push_back({left + 1, mid, r.end});
    todo.push_back({left, r.begin, mid});
  }
  slots_.resize(n);
  slot_of_.resize(n);
  for (int k = 0; k < n; ++k) {
    slots_[k].id = items[k].id;
    slot_of_[items[k].id] = k;
  }
  triangles_ = soup.triangles;
  refit(soup.points);
}

void TriangleBvh::refit(const std::vector<Eigen::Vector3d>& points) {
  if (!slots_.empty() && size_t(max_index_) >= points.size())
    throw std::out_of_range("TriangleBvh::refit: fewer points than the triangles use");
  for (Slot& s : slots_) {
    for (int c = 0; c < 3; ++c) s.corner[c] = points[triangles_[s.id][c]];
    // A sliver's cross product loses its direction to cancellation: it gets no plane test.
    const Eigen::Vector3d e0 = s.corner[1] - s.corner[0], e1 = s.corner[2] - s.corner[0];
    const Eigen::Vector3d n = e0.cross(e1);
    const double len = n.norm();
    const bool well_shaped = std::isfinite(len) && len > kMinSine * e0.norm() * e1.norm();
    for (int k = 0; k < 3; ++k) s.normal[k] = well_shaped ? float(n[k] / len) : 0.0f;
  }
  // Children come after their parent: from the last node back, every child's box is ready before its parent's.
  for (size_t i = nodes_.size(); i-- > 0;) {
    Node& nd = nodes_[i];
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    if (nd.count > 0) {
      for (int s = nd.first; s < nd.first + nd.count; ++s)
        for (const Eigen::Vector3d& p : slots_[s].corner) {
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
      // closest_barycentric() rebuilds the nearest point from the corners: it may land a few units in the
      // last place outside their box, nearer than the box says, which a relative slack cannot cover when
      // the distance is near zero (a query on the surface). The margin keeps every such point inside.
      const double margin = kMarginUlps * std::numeric_limits<double>::epsilon() *
                            std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
      if (std::isfinite(margin)) {
        lo.array() -= margin;
        hi.array() += margin;
      }
    } else {
      for (int c = nd.first; c < nd.first + 2; ++c) {
        lo = lo.cwiseMin(Eigen::Vector3d(nodes_[c].lo[0], nodes_[c].lo[1], nodes_[c].lo[2]));
        hi = hi.cwiseMax(Eigen::Vector3d(nodes_[c].hi[0], nodes_[c].hi[1], nodes_[c].hi[2]));
      }
    }
    for (int k = 0; k < 3; ++k) {
      nd.lo[k] = lo[k];
      nd.hi[k] = hi[k];
    }
  }
}

double TriangleBvh::box_distance2(const Node& n, const Eigen::Vector3d& q) const {
  double d = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double below = n.lo[i] - q[i], above = q[i] - n.hi[i];
    if (below > 0.0)
      d += below * below;
    else if (above > 0.0)
      d += above * above;
  }
  return d;
}

void TriangleBvh::consider(int s, const Eigen::Vector3d& q, double& best, int& best_id) const {
  const Slot& t = slots_[s];
  // The triangle's own box first, widened as a leaf's is: most triangles of an open leaf lie farther than
  // the best already found, and the box says so for a fraction of the closest point's price.
  if (best < HUGE_VAL) {
    const Eigen::Vector3d lo = t.corner[0].cwiseMin(t.corner[1]).cwiseMin(t.corner[2]);
    const Eigen::Vector3d hi = t.corner[0].cwiseMax(t.corner[1]).cwiseMax(t.corner[2]);
    const double margin = kMarginUlps * std::numeric_limits<double>::epsilon() *
                          std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    double d = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double below = lo[i] - margin - q[i], above = q[i] - hi[i] - margin;
      if (below > 0.0)
        d += below * below;
      else if (above > 0.0)
        d += above * above;
    }
    if (d * (1.0 - kSlack) > best) return;
    // Then its plane, which is never farther than the triangle: of the triangles whose boxes reach the
    // query, most lie beside the nearest one on a curved surface, off its plane. The margin covers the
    // normal's rounding to float (relative to the offset) and the corner's to double (relative to the
    // coordinates), so that the test never passes over the triangle the full search would take.
    const Eigen::Vector3d off = q - t.corner[0];
    const double plane = std::abs(t.normal[0] * off[0] + t.normal[1] * off[1] + t.normal[2] * off[2]);
    const double slack = kNormalUlps * std::numeric_limits<float>::epsilon() * off.cwiseAbs().sum() + margin +
                         kMarginUlps * std::numeric_limits<double>::epsilon() * q.cwiseAbs().maxCoeff();
    const double below = plane - slack;
    if (below > 0.0 && below * below * (1.0 - kSlack) > best) return;
  }
  Eigen::Vector3d bary;
  const double d = closest_barycentric(t.corner, q, bary);
  if (!(d < HUGE_VAL)) return;  // a query that is not a number is nearest to nothing
  if (d < best || (d == best && t.id < best_id)) {
    best = d;
    best_id = t.id;
  }
}

double TriangleBvh::distance2_to(const Eigen::Vector3d& q, int triangle) const {
  if (triangle < 0 || size_t(triangle) >= slot_of_.size()) return HUGE_VAL;
  Eigen::Vector3d bary;
  const double d = closest_barycentric(slots_[slot_of_[triangle]].corner, q, bary);
  return d < HUGE_VAL ? d : HUGE_VAL;
}

double TriangleBvh::nearest(const Eigen::Vector3d& q, int& triangle, int hint) const {
  triangle = -1;
  if (slots_.empty()) return HUGE_VAL;
  double best = HUGE_VAL;
  int best_id = INT_MAX;
  if (hint >= 0 && size_t(hint) < slot_of_.size()) consider(slot_of_[hint], q, best, best_id);
  // Depth first, the nearer child on top: each level adds at most one entry, and the depth is about
  // log2 of the triangle count (median splits).
  struct Entry {
    int node;
    double d2;
  };
  Entry stack[128];
  int sp = 0;
  stack[sp++] = {0, box_distance2(nodes_[0], q)};
  auto open = [&best](double d2) { return d2 * (1.0 - kSlack) <= best; };
  while (sp > 0) {
    const Entry e = stack[--sp];
    if (!open(e.d2)) continue;
    const Node& n = nodes_[e.node];
    if (n.count > 0) {
      for (int s = n.first; s < n.first + n.count; ++s) consider(s, q, best, best_id);
      continue;
    }
    const double dl = box_distance2(nodes_[n.first], q), dr = box_distance2(nodes_[n.first + 1], q);
    const Entry near = dl <= dr ? Entry{n.first, dl} : Entry{n.first + 1, dr};
    const Entry far = dl <= dr ? Entry{n.first + 1, dr} : Entry{n.first, dl};
    if (open(far.d2)) stack[sp++] = far;
    if (open(near.d2)) stack[sp++] = near;
  }
  if (best_id == INT_MAX) return HUGE_VAL;
  triangle = best_id;
  return best;
}

}  // namespace OpenMeshSkinned
