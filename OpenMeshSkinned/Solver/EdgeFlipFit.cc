#include "OpenMeshSkinned/Solver/EdgeFlipFit.hh"

#include "OpenMeshSkinned/Eval/SurfaceDistance.hh"
#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Mesh/Seams.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Solver/FitSamples.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <type_traits>

namespace OpenMeshSkinned {

namespace {

using HH = SkinnedMesh::HalfedgeHandle;

// An edge ab that may flip: its faces abc (f1) and bad (f2); flipped, adc and dbc.
struct Quad {
  SkinnedMesh::EdgeHandle edge;
  int f1, f2;
  int a, b, c, d;
};

// Where a face is sampled: the centroid and three points toward the corners (the corners themselves do
// not move with a flip).
constexpr double kBary[4][3] = {
    {1.0 / 3, 1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};

bool same_corner(const SkinnedMesh& mesh, const std::vector<CornerChannel>& channels, HH x, HH y) {
  constexpr double tol2 = kSeamUvTolerance * kSeamUvTolerance;
  if (mesh.has_halfedge_texcoords2D() && double((mesh.texcoord2D(x) - mesh.texcoord2D(y)).sqrnorm()) > tol2)
    return false;
  // The exporter recomputes normals from the faces (ExportCorners.hh): stored ones only say which corners
  // are smoothed together, so corners within kHardEdgeNormalCos of each other are one.
  if (mesh.has_halfedge_normals()) {
    const auto nx = mesh.normal(x), ny = mesh.normal(y);
    const double l = double(nx.norm()) * ny.norm();
    if (l > 0.0 && double(nx | ny) < kHardEdgeNormalCos * l) return false;
  }
  for (const CornerChannel& ch : channels)
    if (double((mesh.property(ch.handle, x) - mesh.property(ch.handle, y)).sqrnorm()) > tol2) return false;
  return true;
}

// The edges that may flip as far as the mesh's connectivity and attributes go.
// \p near: only edges with a vertex flagged there (empty: all).
std::vector<Quad> flippable(const SkinnedMesh& mesh, const std::vector<CornerChannel>& channels,
                            const std::vector<char>& near) {
  OpenMesh::FPropHandleT<int> h_mat;
  const bool has_mat = mesh.get_property_handle(h_mat, prop_names::kFaceMaterial);
  std::vector<Quad> out;
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh) || !mesh.is_flip_ok(eh)) continue;
    const HH h0 = mesh.halfedge_handle(eh, 0), h1 = mesh.halfedge_handle(eh, 1);
    const HH n1 = mesh.next_halfedge_handle(h0), p1 = mesh.next_halfedge_handle(n1);
    const HH n2 = mesh.next_halfedge_handle(h1), p2 = mesh.next_halfedge_handle(n2);
    const auto f1 = mesh.face_handle(h0), f2 = mesh.face_handle(h1);
    if (has_mat && mesh.property(h_mat, f1) != mesh.property(h_mat, f2)) continue;
    // a's corners are p1 and h1, b's h0 and p2: after the flip each keeps one of them.
    if (!same_corner(mesh, channels, p1, h1) || !same_corner(mesh, channels, h0, p2)) continue;
    const Quad q{eh,
                 f1.idx(),
                 f2.idx(),
                 mesh.from_vertex_handle(h0).idx(),
                 mesh.to_vertex_handle(h0).idx(),
                 mesh.to_vertex_handle(n1).idx(),
                 mesh.to_vertex_handle(n2).idx()};
    if (near.empty() || near[q.a] || near[q.b] || near[q.c] || near[q.d]) out.push_back(q);
  }
  return out;
}

double tri_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                     const Eigen::Vector3d& z) {
  const Eigen::Vector3d t[3] = {x, y, z};
  Eigen::Vector3d bary;
  return closest_barycentric(t, p, bary);
}

// The posed original: its search hierarchy, its soup and its smooth (area-weighted) vertex normals.
struct PosedOriginal {
  const MeasuredSurface& surface;
  const TriangleSoup& soup;
  std::vector<Eigen::Vector3d> normal;
};

// Per vertex, the cross products of the triangles around it summed: twice their area-weighted normal, the
// normal the exporter recomputes once normalised.
std::vector<Eigen::Vector3d> normal_sums(const std::vector<Eigen::Vector3d>& p,
                                         const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Eigen::Vector3d> sums(p.size(), Eigen::Vector3d::Zero());
  for (const auto& t : triangles) {
    const Eigen::Vector3d x = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    for (int v : t) sums[v] += x;
  }
  return sums;
}

Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& v) {
  const double l = v.norm();
  return l > 0.0 ? Eigen::Vector3d(v / l) : Eigen::Vector3d::Zero();
}

// Of a triangle's samples, area-weighted: the squared distance to the original, and how far the normal the
// exporter would interpolate there (from the corners' unnormalised normal sums \p s) turns from the original's
// at the nearest point (1 - cos). \p hint: the original's triangle the last query hit.
struct Terms {
  double distance = 0.0, normal = 0.0;
};
Terms face_terms(const PosedOriginal& o, const Eigen::Vector3d (&x)[3], const Eigen::Vector3d (&s)[3], int& hint) {
  const double area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
  const Eigen::Vector3d u[3] = {unit_or_zero(s[0]), unit_or_zero(s[1]), unit_or_zero(s[2])};
  Terms t;
  for (const auto& w : kBary) {
    const Eigen::Vector3d p = w[0] * x[0] + w[1] * x[1] + w[2] * x[2];
    int tri = -1;
    const double dist = o.surface.distance(p, tri, hint);
    if (tri < 0) continue;
    hint = tri;
    t.distance += dist * dist;
    const auto& T = o.soup.triangles[tri];
    const Eigen::Vector3d corners[3] = {o.soup.points[T[0]], o.soup.points[T[1]], o.soup.points[T[2]]};
    Eigen::Vector3d bary;
    closest_barycentric(corners, p, bary);
    const Eigen::Vector3d n_orig =
        unit_or_zero(bary[0] * o.normal[T[0]] + bary[1] * o.normal[T[1]] + bary[2] * o.normal[T[2]]);
    const Eigen::Vector3d n_lod = unit_or_zero(w[0] * u[0] + w[1] * u[1] + w[2] * u[2]);
    t.normal += 1.0 - n_lod.dot(n_orig);
  }
  t.distance *= area / 4.0;
  t.normal *= area / 4.0;
  return t;
}

// One pose's errors of every quad as it is and flipped, and whether the flip keeps it from folding there.
struct PoseErrors {
  std::vector<double> before, after;
  std::vector<double> area;                         // the two faces' area
  std::vector<double> normal_before, normal_after;  // how far the shading normals turn from the original's
  std::vector<char> ok;
  std::vector<int> sample_face;  // the LOD face each of the original's samples is nearest to (-1: not asked)
};

struct SweepInput {
  const SkinnedMesh& lod;
  const SkinnedMesh& original;
  const std::vector<std::array<int, 3>>& triangles;  // the original's
  const std::vector<size_t>& samples;                // vertices, then triangles offset by the vertex count
  const std::vector<Quad>& quads;
  const std::vector<char>* sample_mask = nullptr;  // only these samples are bucketed (null: all)
};

void pose_errors(const SweepInput& in, const Pose& pose, std::unique_ptr<MeasuredSurface>& slot, PoseErrors& out) {
  const SkinnedMesh& original = in.original;
  TriangleSoup posed;
  posed.points = skin_positions(original, pose);
  posed.triangles = in.triangles;
  const MeasuredSurface& surface = posed_surface(slot, posed, 0, 1);
  PosedOriginal po{surface, posed, normal_sums(posed.points, in.triangles)};
  for (auto& n : po.normal) n = unit_or_zero(n);
  double area = 0.0;
  for (const auto& t : in.triangles)
    area += 0.5 * (posed.points[t[1]] - posed.points[t[0]]).cross(posed.points[t[2]] - posed.points[t[0]]).norm();
  const double w_sample = area / double(std::max<size_t>(1, in.samples.size()));

  const TriangleSoup lsoup = posed_soup(in.lod, pose);
  const MeasuredSurface lsurf(lsoup, 0, 1);
  const std::vector<Eigen::Vector3d>& y = lsoup.points;
  const std::vector<Eigen::Vector3d> sums = normal_sums(y, lsoup.triangles);
  // The original's samples, by the LOD face nearest to them (the soup's triangles are the faces in order).
  const size_t nf = in.lod.n_faces();
  std::vector<Eigen::Vector3d> at(in.samples.size());
  std::vector<int> face(in.samples.size(), -1);
  std::vector<double> d2(in.samples.size(), 0.0);
  std::vector<int> start(nf + 1, 0);
  int previous = -1;
  for (size_t k = 0; k < in.samples.size(); ++k) {
    if (in.sample_mask && !(*in.sample_mask)[k]) continue;
    at[k] = sample_point(posed.points, in.triangles, original.n_vertices(), in.samples[k]);
    int tri = -1;
    const double dist = lsurf.distance(at[k], tri, previous);
    if (tri < 0) continue;
    previous = tri;
    face[k] = tri;
    d2[k] = dist * dist;
    ++start[tri + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  out.sample_face = face;
  std::vector<int> bucket(start[nf]);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t k = 0; k < face.size(); ++k)
      if (face[k] >= 0) bucket[fill[face[k]]++] = int(k);
  }

  // Each LOD vertex's nearest triangle of the original starts the searches of the samples beside it.
  std::vector<int> near_tri(y.size(), -2);  // -2: not searched yet
  int last_tri = -1;
  auto hint_at = [&](int v) {
    if (near_tri[v] == -2) {
      surface.distance(y[v], near_tri[v], last_tri);
      if (near_tri[v] >= 0) last_tri = near_tri[v];
    }
    return near_tri[v];
  };
  // Each face's own term once, when first asked for: it is the "before" of all three of its edges.
  std::vector<Terms> face_term(nf, Terms{-1.0, -1.0});
  auto term_of = [&](int f) {
    if (face_term[f].distance < 0.0) {
      const auto& T = lsoup.triangles[f];
      int hint = hint_at(T[0]);
      face_term[f] = face_terms(po, {y[T[0]], y[T[1]], y[T[2]]}, {sums[T[0]], sums[T[1]], sums[T[2]]}, hint);
    }
    return face_term[f];
  };
  const size_t nq = in.quads.size();
  out.before.assign(nq, 0.0);
  out.after.assign(nq, 0.0);
  out.ok.assign(nq, 0);
  out.area.assign(nq, 0.0);
  out.normal_before.assign(nq, 0.0);
  out.normal_after.assign(nq, 0.0);
  for (size_t q = 0; q < nq; ++q) {
    const Quad& Q = in.quads[q];
    const Eigen::Vector3d &a = y[Q.a], &b = y[Q.b], &c = y[Q.c], &d = y[Q.d];
    const Eigen::Vector3d m = (b - a).cross(c - a) + (a - b).cross(d - b);
    const Eigen::Vector3d n1 = (d - a).cross(c - a), n2 = (b - d).cross(c - d);
    const double scale = m.squaredNorm();
    // Neither new face degenerate, the two not folded onto each other, neither turned from the old pair.
    const bool ok = n1.squaredNorm() > 1e-12 * scale && n2.squaredNorm() > 1e-12 * scale && n1.dot(n2) > 0.0 &&
                    n1.dot(m) > 0.0 && n2.dot(m) > 0.0;
    out.ok[q] = ok;
    if (!ok) continue;
    out.area[q] = 0.5 * ((b - a).cross(c - a).norm() + (a - b).cross(d - b).norm());
    const Terms t1 = term_of(Q.f1), t2 = term_of(Q.f2);
    double before = t1.distance + t2.distance;
    // The four corners' normal sums with the old faces' cross products out and the new ones in.
    const Eigen::Vector3d x1 = (b - a).cross(c - a), x2 = (a - b).cross(d - b);
    const Eigen::Vector3d sa = sums[Q.a] - x1 - x2 + n1, sb = sums[Q.b] - x1 - x2 + n2, sc = sums[Q.c] - x1 + n1 + n2,
                          sd = sums[Q.d] - x2 + n1 + n2;
    int hint = hint_at(Q.c);
    const Terms u1 = face_terms(po, {a, d, c}, {sa, sd, sc}, hint);
    hint = hint_at(Q.c);
    const Terms u2 = face_terms(po, {d, b, c}, {sd, sb, sc}, hint);
    double after = u1.distance + u2.distance;
    out.normal_before[q] = t1.normal + t2.normal;
    out.normal_after[q] = u1.normal + u2.normal;
    for (const int f : {Q.f1, Q.f2})
      for (int s = start[f]; s < start[f + 1]; ++s) {
        const int k = bucket[s];
        before += w_sample * d2[k];
        after += w_sample * std::min(tri_distance2(at[k], a, d, c), tri_distance2(at[k], d, b, c));
      }
    out.before[q] = before;
    out.after[q] = after;
  }
}

// The poses of the screen: \p n of \p count, evenly spread, both ends included (all when n <= 0 or n >= count).
std::vector<size_t> screen_poses(size_t count, int n) {
  std::vector<size_t> out;
  if (n <= 0 || size_t(n) >= count) {
    for (size_t j = 0; j < count; ++j) out.push_back(j);
    return out;
  }
  for (int i = 0; i < n; ++i) {
    const size_t j = n == 1 ? 0 : size_t(std::lround(double(i) * double(count - 1) / double(n - 1)));
    if (out.empty() || out.back() != j) out.push_back(j);
  }
  return out;
}

// \p e's entries at \p index, in that order.
void select(PoseErrors& e, const std::vector<size_t>& index) {
  auto pick = [&](auto& v) {
    std::decay_t<decltype(v)> out(index.size());
    for (size_t i = 0; i < index.size(); ++i) out[i] = v[index[i]];
    v.swap(out);
  };
  pick(e.before);
  pick(e.after);
  pick(e.area);
  pick(e.normal_before);
  pick(e.normal_after);
  pick(e.ok);
}

// The original's samples the quads \p quads are judged on outside the screen: those that lay nearest, in one
// of the poses of \p faces (each sample's nearest LOD face, -1: not known), to a face sharing a vertex with a
// quad. A sample that is nearest to one of the quad's two faces in another pose, or after a flip nearby,
// without ever lying within that ring in the screen is left out: it would have to cross more than a ring of
// faces between poses.
std::vector<char> samples_near(const SkinnedMesh& lod, const std::vector<Quad>& quads,
                               const std::vector<std::vector<int>>& faces) {
  std::vector<char> face_near(lod.n_faces(), 0);
  for (const Quad& q : quads)
    for (const int v : {q.a, q.b, q.c, q.d})
      for (auto fh : lod.vf_range(SkinnedMesh::VertexHandle(v))) face_near[fh.idx()] = 1;
  std::vector<char> mask;
  for (const std::vector<int>& face : faces) {
    mask.resize(face.size(), 0);
    for (size_t k = 0; k < face.size(); ++k)
      if (face[k] >= 0 && face_near[face[k]]) mask[k] = 1;
  }
  return mask;
}

void run_poses(const SweepInput& in, const std::vector<Pose>& poses, const std::vector<size_t>& which, int threads,
               std::vector<std::unique_ptr<MeasuredSurface>>& slots, std::vector<PoseErrors>& out) {
  std::atomic<size_t> next{0};
  run_on_threads(std::max(1, std::min<int>(threads, int(which.size()))), [&](int t) {
    for (size_t i = next++; i < which.size(); i = next++) pose_errors(in, poses[which[i]], slots[t], out[which[i]]);
  });
}

// Every pose's errors of the quads that pass the screen, in \p per_pose (indexed as the returned quads). The
// screen is a few poses spread over the list: a quad whose flip folds in one of them, or at least doubles its
// error summed over them, is not judged in the others. In those, only the original's samples that lay near
// a kept quad in the screen are placed on the LOD (samples_near). \p screen_faces: where each sample last lay
// on the LOD in each of the screen's poses (empty before the first sweep; updated here), which places the
// later sweeps' screens' samples the same way. Without a screen (every pose in it) every sample of every pose
// is placed.
std::vector<Quad> screened_errors(const SweepInput& all, const std::vector<Pose>& poses,
                                  const FlipFitSettings& settings, int threads,
                                  std::vector<std::unique_ptr<MeasuredSurface>>& slots,
                                  std::vector<std::vector<int>>& screen_faces, std::vector<PoseErrors>& per_pose) {
  const std::vector<size_t> screen = screen_poses(poses.size(), settings.screen_poses);
  if (screen.size() == poses.size()) {
    run_poses(all, poses, screen, threads, slots, per_pose);
    return all.quads;
  }
  const std::vector<char> screen_mask =
      screen_faces.empty() ? std::vector<char>{} : samples_near(all.lod, all.quads, screen_faces);
  SweepInput in = all;
  in.sample_mask = screen_faces.empty() ? nullptr : &screen_mask;
  run_poses(in, poses, screen, threads, slots, per_pose);
  screen_faces.resize(screen.size());
  for (size_t i = 0; i < screen.size(); ++i) {
    const std::vector<int>& now = per_pose[screen[i]].sample_face;
    if (screen_faces[i].empty()) {
      screen_faces[i] = now;
      continue;
    }
    for (size_t k = 0; k < now.size(); ++k)
      if (now[k] >= 0) screen_faces[i][k] = now[k];
  }

  std::vector<Quad> kept;
  std::vector<size_t> kept_index;
  for (size_t q = 0; q < all.quads.size(); ++q) {
    bool ok = true;
    double before = 0.0, after = 0.0;
    for (size_t j : screen) {
      ok = ok && per_pose[j].ok[q];
      before += per_pose[j].before[q];
      after += per_pose[j].after[q];
    }
    if (ok && !(after >= 2.0 * before && after > 0.0)) {
      kept.push_back(all.quads[q]);
      kept_index.push_back(q);
    }
  }
  for (size_t j : screen) select(per_pose[j], kept_index);
  if (kept.empty()) return kept;
  std::vector<char> in_screen(poses.size(), 0);
  for (size_t j : screen) in_screen[j] = 1;
  std::vector<size_t> rest;
  for (size_t j = 0; j < poses.size(); ++j)
    if (!in_screen[j]) rest.push_back(j);
  const std::vector<char> mask = samples_near(all.lod, kept, screen_faces);
  const SweepInput judged{all.lod, all.original, all.triangles, all.samples, kept, &mask};
  run_poses(judged, poses, rest, threads, slots, per_pose);
  return kept;
}

// Flips \p e and gives the two halfedges it turned into the corners of the vertices they now point to.
void flip_keeping_corners(SkinnedMesh& mesh, SkinnedMesh::EdgeHandle e, const std::vector<CornerChannel>& channels) {
  const HH h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  const HH n1 = mesh.next_halfedge_handle(h0), n2 = mesh.next_halfedge_handle(h1);  // b->c and a->d
  mesh.flip(e);
  for (const HH h : {mesh.halfedge_handle(e, 0), mesh.halfedge_handle(e, 1)}) {
    const HH from = mesh.to_vertex_handle(h) == mesh.to_vertex_handle(n1) ? n1 : n2;
    if (mesh.has_halfedge_texcoords2D()) mesh.set_texcoord2D(h, mesh.texcoord2D(from));
    if (mesh.has_halfedge_normals()) mesh.set_normal(h, mesh.normal(from));
    for (const CornerChannel& ch : channels) mesh.property(ch.handle, h) = mesh.property(ch.handle, from);
  }
}

}  // namespace

FlipFitReport flip_edges_to_fit(SkinnedMesh& lod, const SkinnedMesh& original, const std::vector<Pose>& poses,
                                const FlipFitSettings& settings) {
  FlipFitReport report;
  if (poses.empty() || lod.n_faces() < 2 || original.n_faces() == 0) return report;
  const std::vector<std::array<int, 3>> triangles = mesh_triangles(original);
  const std::vector<size_t> samples = strided_samples(original, triangles.size(), settings.max_samples);
  const std::vector<CornerChannel> channels = corner_channels(lod);
  const double diagonal = bbox_diagonal(original);
  const int threads = std::max(1, std::min<int>(settings.threads, int(poses.size())));
  std::vector<std::unique_ptr<MeasuredSurface>> slots(threads);
  // After the first sweep, only edges near a flip can have changed their answer.
  std::vector<char> near;
  // Where the original's samples lay on the LOD in the screen's poses, for the later sweeps' screens.
  std::vector<std::vector<int>> screen_faces;
  for (int sweep = 0; sweep < settings.sweeps; ++sweep) {
    const std::vector<Quad> quads = flippable(lod, channels, near);
    if (quads.empty()) break;
    std::vector<PoseErrors> per_pose(poses.size());
    const SweepInput in{lod, original, triangles, samples, quads};
    const std::vector<Quad> kept = screened_errors(in, poses, settings, threads, slots, screen_faces, per_pose);
    // Summed in pose order, so that the answer does not depend on the thread count.
    std::vector<std::pair<double, size_t>> gains;
    std::vector<double> before(kept.size(), 0.0), after(kept.size(), 0.0);
    const double floor = settings.tolerance * diagonal * settings.tolerance * diagonal;
    for (size_t q = 0; q < kept.size(); ++q) {
      bool ok = true;
      double area = 0.0, normal_before = 0.0, normal_after = 0.0;
      for (const PoseErrors& p : per_pose) {
        ok = ok && p.ok[q];
        before[q] += p.before[q];
        after[q] += p.after[q];
        area += p.area[q];
        normal_before += p.normal_before[q];
        normal_after += p.normal_after[q];
      }
      // Nor one that turns the shading further from the original's on the quad.
      ok = ok && normal_after <= normal_before;
      // A quad that already fits gains only rounding: both diagonals lie on the surface.
      const double gain = before[q] - after[q];
      if (ok && gain > settings.min_gain * before[q] && gain > floor * area) gains.push_back({gain, q});
    }
    std::sort(gains.begin(), gains.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    std::vector<char> touched(lod.n_faces(), 0);
    near.assign(lod.n_vertices(), 0);
    int flips = 0;
    for (const auto& [gain, q] : gains) {
      const Quad& Q = kept[q];
      if (touched[Q.f1] || touched[Q.f2] || !lod.is_flip_ok(Q.edge)) continue;
      touched[Q.f1] = touched[Q.f2] = 1;
      near[Q.a] = near[Q.b] = near[Q.c] = near[Q.d] = 1;
      flip_keeping_corners(lod, Q.edge, channels);
      report.before += before[q];
      report.after += after[q];
      ++flips;
    }
    if (flips == 0) break;
    report.flips += flips;
    ++report.sweeps;
  }
  if (report.flips > 0 && lod.has_face_normals()) lod.update_face_normals();
  return report;
}

}  // namespace OpenMeshSkinned
