#include "OpenMeshSkinned/Mesh/Procedural.hh"

#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {
namespace {

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Eigen::Matrix4d translation(double x, double y, double z) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 3) = x;
  m(1, 3) = y;
  m(2, 3) = z;
  return m;
}

// Point on the unit square's outline (perimeter parameter u in [0,1)), for the square column.
Eigen::Vector2d square_outline(double u) {
  const double s = 4.0 * u;
  const int side = std::min(3, static_cast<int>(s));
  const double t = s - side;
  switch (side) {
    case 0:
      return {1.0, -1.0 + 2.0 * t};
    case 1:
      return {1.0 - 2.0 * t, 1.0};
    case 2:
      return {-1.0, 1.0 - 2.0 * t};
    default:
      return {-1.0 + 2.0 * t, -1.0};
  }
}

// A chain of nb bones along +y, each bone_len long.
Skeleton tube_skeleton(int nb, double bone_len) {
  Skeleton skel;
  for (int b = 0; b < nb; ++b) {
    Joint j;
    j.name = "bone" + std::to_string(b);
    j.parent = b - 1;
    j.rest_local = translation(0, b == 0 ? 0.0 : bone_len, 0);
    j.inverse_bind = translation(0, -b * bone_len, 0);
    skel.joints.push_back(j);
  }
  return skel;
}

// The skin at height y: bone b owns [b, b+1) * bone_len; blend across each joint over +-blend*length.
Influences tube_influences(const TubeOptions& opt, int nb, double bone_len, double y) {
  Influences inf;
  double w_prev = 1.0;
  std::vector<double> w(nb, 0.0);
  for (int b = 1; b < nb; ++b) {
    const double s = smoothstep(b * bone_len - opt.blend * opt.length, b * bone_len + opt.blend * opt.length, y);
    w[b - 1] = w_prev - s * w_prev;
    w_prev = s * w_prev;
  }
  w[nb - 1] = w_prev;
  for (int b = 0; b < nb; ++b)
    if (w[b] > 1e-12) inf.push(b, w[b]);
  inf.normalize();
  inf.sort();
  return inf;
}

// Rings of opt.around vertices at opt.along + 1 heights, joined by triangles of material 0, with
// corner normals pointing straight out from the axis.
void add_tube_surface(SkinnedMesh& mesh, const TubeOptions& opt, int nb, double bone_len) {
  const auto h_inf = influences_handle(mesh);
  const auto h_mat = face_material_handle(mesh);
  std::vector<SkinnedMesh::VertexHandle> vh;
  for (int i = 0; i <= opt.along; ++i) {
    const double y = opt.length * i / opt.along;
    const double r = opt.radius_base + (opt.radius_tip - opt.radius_base) * y / opt.length;
    const Influences inf = tube_influences(opt, nb, bone_len, y);
    for (int k = 0; k < opt.around; ++k) {
      const double u = static_cast<double>(k) / opt.around;
      Eigen::Vector2d xz =
          opt.square ? square_outline(u) : Eigen::Vector2d(std::cos(2 * M_PI * u), std::sin(2 * M_PI * u));
      const auto v = mesh.add_vertex(SkinnedMesh::Point(r * xz.x(), y, r * xz.y()));
      mesh.property(h_inf, v) = inf;
      vh.push_back(v);
    }
  }
  for (int i = 0; i < opt.along; ++i)
    for (int k = 0; k < opt.around; ++k) {
      const int k1 = (k + 1) % opt.around;
      const auto a = vh[i * opt.around + k], b = vh[i * opt.around + k1];
      const auto c = vh[(i + 1) * opt.around + k], d = vh[(i + 1) * opt.around + k1];
      // Outward-facing: the outline runs counter-clockwise seen from +y.
      mesh.property(h_mat, mesh.add_face(a, c, b)) = 0;
      mesh.property(h_mat, mesh.add_face(b, c, d)) = 0;
    }
  mesh.update_face_normals();
  clear_corner_attributes(mesh);
  for (auto heh : mesh.halfedges())
    if (!mesh.is_boundary(heh)) {
      const auto v = mesh.to_vertex_handle(heh);
      const auto p = mesh.point(v);
      auto n = SkinnedMesh::Normal(p[0], 0.0, p[2]);
      if (n.norm() > 0) n.normalize();
      mesh.set_normal(heh, n);
    }
}

// Every joint but the root turning by bend_degrees about x over one second.
Clip bend_clip(int nb, double bend_degrees) {
  Clip clip;
  clip.name = "bend";
  clip.duration = 1.0;
  const Eigen::Quaterniond bent(Eigen::AngleAxisd(bend_degrees * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  for (int b = 1; b < nb; ++b) {
    Channel ch;
    ch.joint = b;
    ch.rotation_times = {0.0, 1.0};
    ch.rotations = {Eigen::Quaterniond::Identity(), bent};
    clip.channels.push_back(ch);
  }
  return clip;
}

}  // namespace

SkinnedMesh make_skinned_tube(const TubeOptions& opt, double bend_degrees) {
  SkinnedMesh mesh;
  request_skinned_attributes(mesh);
  add_skin(mesh);
  const int nb = std::max(1, opt.bones);
  const double bone_len = opt.length / nb;
  skeleton(mesh) = tube_skeleton(nb, bone_len);
  add_tube_surface(mesh, opt, nb, bone_len);
  Material mat;
  mat.name = opt.square ? "column" : "leg";
  mat.base_color[0] = 0.8;
  mat.base_color[1] = 0.6;
  mat.base_color[2] = 0.5;
  materials(mesh).push_back(mat);
  clips(mesh).push_back(bend_clip(nb, bend_degrees));
  example_poses(mesh) = {Pose::identity(nb)};
  return mesh;
}

SkinnedMesh make_bending_cylinder(int around, int along) {
  TubeOptions opt;
  opt.around = around;
  opt.along = along;
  opt.bones = 2;
  SkinnedMesh mesh = make_skinned_tube(opt, 90.0);
  example_poses(mesh) = sample_poses_at(skeleton(mesh), clips(mesh)[0], {0.0, 1.0});
  return mesh;
}

SkinnedMesh make_square_column(int around, int along) {
  TubeOptions opt;
  opt.around = around;
  opt.along = along;
  opt.square = true;
  opt.length = 8.0;
  opt.radius_base = opt.radius_tip = 0.5;
  opt.bones = 4;
  opt.blend = 0.08;
  SkinnedMesh mesh = make_skinned_tube(opt, 30.0);
  Skeleton& skel = skeleton(mesh);
  // Four example poses: every joint bent 30 degrees forward, back, left, right.
  const Eigen::Vector3d axes[4] = {Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                   -Eigen::Vector3d::UnitZ()};
  Clip sway;
  sway.name = "sway";
  sway.duration = 3.0;
  for (int b = 1; b < skel.size(); ++b) {
    Channel ch;
    ch.joint = b;
    for (int p = 0; p < 4; ++p) {
      ch.rotation_times.push_back(p);
      ch.rotations.emplace_back(Eigen::AngleAxisd(30.0 * M_PI / 180.0, axes[p]));
    }
    sway.channels.push_back(ch);
  }
  clips(mesh) = {sway};
  example_poses(mesh) = sample_poses_at(skel, sway, {0.0, 1.0, 2.0, 3.0});
  return mesh;
}

void diffuse_skin_weights(SkinnedMesh& mesh, int steps, int max_influences) {
  const auto h = influences_handle(mesh);
  std::vector<Influences> next(mesh.n_vertices());
  for (int step = 0; step < steps; ++step) {
    for (auto vh : mesh.vertices()) {
      InfluenceSum sum;
      sum.add(mesh.property(h, vh), 0.5);
      const double n = static_cast<double>(mesh.valence(vh));
      for (auto nb : mesh.vv_range(vh)) sum.add(mesh.property(h, nb), 0.5 / n);
      if (n == 0) sum.add(mesh.property(h, vh), 0.5);
      next[vh.idx()] = sum.keep_heaviest(max_influences);
    }
    for (auto vh : mesh.vertices()) mesh.property(h, vh) = next[vh.idx()];
  }
}

}  // namespace OpenMeshSkinned
