#include "OpenMeshSkinned/Mesh/Tangents.hh"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

namespace OpenMeshSkinned {
namespace {

// A triangle whose UV area or area is this small against its edges' lengths has no frame of its own: its
// u direction is rounding noise (float UVs of a small triangle carry about six digits).
constexpr double kDegenerate = 1e-6;

// Corners that may share a tangent: one vertex, normal and UV; \c sign apart (mirrored UVs at a seam).
struct Key {
  int vertex;
  std::array<double, 3> n;
  std::array<double, 2> uv;
  int sign;
  bool operator<(const Key& o) const { return std::tie(vertex, n, uv, sign) < std::tie(o.vertex, o.n, o.uv, o.sign); }
};

Key key_of(const TangentCorner& c, int sign) {
  return {c.vertex, {c.normal[0], c.normal[1], c.normal[2]}, {c.uv[0], c.uv[1]}, sign};
}

// \p v in the plane orthogonal to \p n, of unit length; false when nothing of it is left.
bool in_plane(const Eigen::Vector3d& v, const Eigen::Vector3d& n, Eigen::Vector3d& out) {
  const Eigen::Vector3d t = v - n * n.dot(v);
  const double len = t.norm();
  if (!(len > 1e-12 * v.norm()) || !std::isfinite(len)) return false;
  out = t / len;
  return true;
}

// A direction orthogonal to \p n for a corner no triangle gives one: the coordinate axis least aligned with
// \p n, made orthogonal to it (the same for every such corner of one normal, so they stay one vertex).
Eigen::Vector3d any_orthogonal(const Eigen::Vector3d& n) {
  int k = 0;
  n.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k);
  Eigen::Vector3d t;
  return in_plane(axis, n, t) ? t : axis;
}

// The angle at \p p between the edges to \p a and \p b (atan2: exact for small and obtuse angles alike).
double corner_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d e = a - p, f = b - p;
  return std::atan2(e.cross(f).norm(), e.dot(f));
}

}  // namespace

std::vector<Eigen::Vector4d> corner_tangents(const std::vector<TangentCorner>& corners) {
  if (corners.size() % 3 != 0) throw std::invalid_argument("corner_tangents: corners do not make whole triangles");
  std::map<Key, Eigen::Vector3d> sums;
  std::vector<int> sign(corners.size(), 0);  // the handedness of each corner's triangle; 0: it has no frame
  for (size_t t = 0; t < corners.size(); t += 3) {
    const TangentCorner *c0 = &corners[t], *c1 = &corners[t + 1], *c2 = &corners[t + 2];
    const Eigen::Vector3d e1 = c1->position - c0->position, e2 = c2->position - c0->position;
    const Eigen::Vector2d s1 = c1->uv - c0->uv, s2 = c2->uv - c0->uv;
    // The positions are an affine function of the UVs over the triangle: e = du T + dv B for both edges.
    const double det = s1.x() * s2.y() - s2.x() * s1.y();
    if (!std::isfinite(det) || !(std::abs(det) > kDegenerate * s1.norm() * s2.norm()) ||
        !(e1.cross(e2).norm() > kDegenerate * e1.norm() * e2.norm()))
      continue;
    const Eigen::Vector3d T = (e1 * s2.y() - e2 * s1.y()) / det;
    // Counter-clockwise in 3D, so the face normal is e1 x e2 = det (T x B): UVs that keep the winding
    // give a right-handed frame (normal x tangent along +v).
    const int s = det > 0.0 ? 1 : -1;
    for (int k = 0; k < 3; ++k) {
      const TangentCorner& c = corners[t + k];
      sign[t + k] = s;
      Eigen::Vector3d dir;
      if (!in_plane(T, c.normal, dir)) continue;
      // Angle weights: a vertex's frame does not change when a face next to it is split in two.
      const double angle =
          corner_angle(c.position, corners[t + (k + 1) % 3].position, corners[t + (k + 2) % 3].position);
      auto [it, fresh] = sums.emplace(key_of(c, s), Eigen::Vector3d::Zero());
      it->second += angle * dir;
    }
  }

  std::vector<Eigen::Vector4d> out(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    const TangentCorner& c = corners[i];
    Eigen::Vector3d dir;
    auto take = [&](const Key& k) {
      const auto it = sums.find(k);
      if (it == sums.end() || !in_plane(it->second, c.normal, dir)) return false;
      out[i] = Eigen::Vector4d(dir[0], dir[1], dir[2], k.sign);
      return true;
    };
    if (sign[i] != 0 && take(key_of(c, sign[i]))) continue;
    if (take(key_of(c, 1)) || take(key_of(c, -1))) continue;
    // No frame of its own (degenerate triangles only, or contributions that cancel): the vertex's other
    // corners, those of the same normal first, as a neighbouring face's frame continues across it.
    const double inf = std::numeric_limits<double>::infinity();
    const auto first = sums.lower_bound(Key{c.vertex, {-inf, -inf, -inf}, {-inf, -inf}, -2});
    bool found = false;
    for (int pass = 0; pass < 2 && !found; ++pass)
      for (auto it = first; it != sums.end() && it->first.vertex == c.vertex && !found; ++it)
        if (pass == 1 || it->first.n == key_of(c, 0).n) found = take(it->first);
    if (found) continue;
    dir = any_orthogonal(c.normal);
    out[i] = Eigen::Vector4d(dir[0], dir[1], dir[2], 1.0);
  }
  return out;
}

}  // namespace OpenMeshSkinned
