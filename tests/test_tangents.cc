// Tangent frames for normal maps (Mesh/Tangents.hh): the u direction in each corner's tangent plane,
// handedness in w, angle-weighted, mirrored islands kept apart, degenerate UV triangles handled.
#include <OpenMeshSkinned/Mesh/Tangents.hh>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace OpenMeshSkinned;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector4d;

namespace {

TangentCorner corner(int vertex, Vector3d p, Vector3d n, Vector2d uv) { return {vertex, p, n.normalized(), uv}; }

// A unit quad in the plane z = 0 facing +z, vertices 0..3 counter-clockwise from the origin, as two
// triangles; \p uv_of gives each corner's UV from its position.
template <typename UvOf>
std::vector<TangentCorner> quad(UvOf uv_of, int first_vertex = 0, double x0 = 0.0) {
  const Vector3d p[4] = {{x0, 0, 0}, {x0 + 1, 0, 0}, {x0 + 1, 1, 0}, {x0, 1, 0}};
  std::vector<TangentCorner> c;
  for (int i : {0, 1, 2, 0, 2, 3}) c.push_back(corner(first_vertex + i, p[i], Vector3d::UnitZ(), uv_of(p[i])));
  return c;
}

void expect_frame(const TangentCorner& c, const Vector4d& t) {
  const Vector3d xyz = t.head<3>();
  EXPECT_NEAR(xyz.norm(), 1.0, 1e-12);
  EXPECT_NEAR(xyz.dot(c.normal), 0.0, 1e-12);
  EXPECT_TRUE(t[3] == 1.0 || t[3] == -1.0) << t[3];
}

}  // namespace

TEST(Tangents, AFlatQuadsTangentIsItsUDirectionRightHanded) {
  // u along x, v along y: normal x tangent = +y = increasing v, so w = +1.
  const auto c = quad([](const Vector3d& p) { return Vector2d(p.x(), p.y()); });
  const auto t = corner_tangents(c);
  ASSERT_EQ(t.size(), c.size());
  for (size_t i = 0; i < c.size(); ++i) {
    expect_frame(c[i], t[i]);
    EXPECT_LT((t[i] - Vector4d(1, 0, 0, 1)).norm(), 1e-12) << i << ": " << t[i].transpose();
  }
  // A rotated, scaled mapping: u along y, v along -x (still right-handed): the tangent follows u.
  const auto r = corner_tangents(quad([](const Vector3d& p) { return Vector2d(3.0 * p.y(), -2.0 * p.x()); }));
  for (const Vector4d& x : r) EXPECT_LT((x - Vector4d(0, 1, 0, 1)).norm(), 1e-12) << x.transpose();
}

TEST(Tangents, MirroredUvsGiveMinusOneAndTheBitangentStillFollowsV) {
  const auto c = quad([](const Vector3d& p) { return Vector2d(1.0 - p.x(), p.y()); });
  const auto t = corner_tangents(c);
  for (size_t i = 0; i < c.size(); ++i) {
    EXPECT_LT((t[i] - Vector4d(-1, 0, 0, -1)).norm(), 1e-12) << t[i].transpose();
    // glTF's bitangent, w (normal x tangent), points along increasing v (+y here).
    const Vector3d b = t[i][3] * c[i].normal.cross(t[i].head<3>());
    EXPECT_GT(b.dot(Vector3d::UnitY()), 0.99);
  }
}

TEST(Tangents, CornersOfOppositeHandednessAtAMirrorSeamAreNotAveraged) {
  // Two quads side by side sharing the edge x = 1 (vertices 1 and 2), the right one's UVs mirrored about
  // the seam, so the seam's corners have one vertex, normal and UV on both sides.
  auto c = quad([](const Vector3d& p) { return Vector2d(p.x(), p.y()); });
  const Vector3d right[4] = {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}};
  const int ids[4] = {1, 4, 5, 2};
  for (int i : {0, 1, 2, 0, 2, 3})
    c.push_back(corner(ids[i], right[i], Vector3d::UnitZ(), Vector2d(2.0 - right[i].x(), right[i].y())));
  const auto t = corner_tangents(c);
  for (size_t i = 0; i < c.size(); ++i) {
    const Vector4d want = i < 6 ? Vector4d(1, 0, 0, 1) : Vector4d(-1, 0, 0, -1);
    EXPECT_LT((t[i] - want).norm(), 1e-12) << "corner " << i << " (vertex " << c[i].vertex << "): " << t[i].transpose();
  }
}

TEST(Tangents, ACylindersTangentsAreOrthogonalToItsNormalsAndFollowU) {
  // Around the y axis, u the angle / 2 pi (a seam at angle 0 where u is 0 on one side and 1 on the
  // other), v the height; faces seen from outside; normals radial.
  const int n = 24, rows = 3;
  auto pos = [&](int i, int j) {
    const double a = 2.0 * M_PI * i / n;
    return Vector3d(std::cos(a), double(j) / rows, -std::sin(a));
  };
  auto vid = [&](int i, int j) { return (i % n) * (rows + 1) + j; };
  std::vector<TangentCorner> c;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < rows; ++j) {
      const int quad_corners[6][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j}, {i + 1, j + 1}, {i, j + 1}};
      for (const auto& q : quad_corners) {
        const Vector3d p = pos(q[0], q[1]);
        c.push_back(corner(vid(q[0], q[1]), p, Vector3d(p.x(), 0, p.z()), Vector2d(double(q[0]) / n, p.y())));
      }
    }
  const auto t = corner_tangents(c);
  for (size_t k = 0; k < c.size(); ++k) {
    expect_frame(c[k], t[k]);
    // d position / d angle at the corner's own angle: exact by symmetry of the faces around each vertex.
    const Vector3d& p = c[k].position;
    const Vector3d du(p.z(), 0.0, -p.x());
    EXPECT_GT(t[k].head<3>().dot(du.normalized()), 1.0 - 1e-9) << k << ": " << t[k].transpose();
    EXPECT_EQ(t[k][3], 1.0);
  }
}

TEST(Tangents, AnglesWeighTheFacesSoSplittingAFaceChangesNothing) {
  // The apex of a pyramid: four faces of different u directions in space. Splitting one face in two
  // through the apex (UVs affine on it) leaves the apex's tangent as it was; counting faces would not.
  const Vector3d apex(0, 0, 1), base[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  const Vector3d n_apex = Vector3d::UnitZ();
  auto uv = [](const Vector3d& p) { return Vector2d(p.x() + 0.3 * p.z(), p.y() + 0.5 * p.z()); };
  std::vector<TangentCorner> whole, split;
  for (int f = 0; f < 4; ++f) {
    const Vector3d a = base[f], b = base[(f + 1) % 4];
    auto tri = [&](std::vector<TangentCorner>& out, const Vector3d& p, const Vector3d& q, int ip, int iq) {
      out.push_back(corner(0, apex, n_apex, uv(apex)));
      out.push_back(corner(ip, p, p, uv(p)));
      out.push_back(corner(iq, q, q, uv(q)));
    };
    tri(whole, a, b, 1 + f, 1 + (f + 1) % 4);
    if (f == 0) {
      const Vector3d m = 0.5 * (a + b);
      tri(split, a, m, 1, 9);
      tri(split, m, b, 9, 2);
    } else {
      tri(split, a, b, 1 + f, 1 + (f + 1) % 4);
    }
  }
  const Vector4d t_whole = corner_tangents(whole)[0], t_split = corner_tangents(split)[0];
  EXPECT_LT((t_whole - t_split).norm(), 1e-12) << t_whole.transpose() << " vs " << t_split.transpose();
  EXPECT_LT(std::abs(t_whole.head<3>().dot(n_apex)), 1e-12);
}

TEST(Tangents, DegenerateUvTrianglesTakeTheirNeighboursFrameOrAnyOrthogonalOne) {
  // The quad's second triangle has all three UVs equal: its vertices 0 and 2 take the first triangle's
  // frame there (same vertex and normal); vertex 3 has no other corner but still gets an orthogonal unit tangent.
  auto c = quad([](const Vector3d& p) { return Vector2d(p.x(), p.y()); });
  for (int k = 3; k < 6; ++k) c[k].uv = Vector2d(0.5, 0.5);
  const auto t = corner_tangents(c);
  for (size_t i = 0; i < c.size(); ++i) {
    expect_frame(c[i], t[i]);
    if (c[i].vertex != 3) {
      EXPECT_LT((t[i] - Vector4d(1, 0, 0, 1)).norm(), 1e-12) << i << ": " << t[i].transpose();
    }
    EXPECT_TRUE(t[i].allFinite());
  }
  // A zero-area triangle (a repeated position) and UVs on a line: finite unit tangents, no NaN.
  std::vector<TangentCorner> d = {corner(0, {0, 0, 0}, {0, 0, 1}, {0, 0}), corner(1, {0, 0, 0}, {0, 0, 1}, {1, 0}),
                                  corner(2, {0, 1, 0}, {0, 0, 1}, {0, 1}), corner(3, {0, 0, 0}, {0, 0, 1}, {0, 0}),
                                  corner(4, {1, 0, 0}, {0, 0, 1}, {1, 1}), corner(5, {0, 1, 0}, {0, 0, 1}, {2, 2})};
  for (size_t i = 0; i < d.size(); ++i) expect_frame(d[i], corner_tangents(d)[i]);
  EXPECT_THROW(corner_tangents(std::vector<TangentCorner>(4, d[0])), std::invalid_argument);
}
