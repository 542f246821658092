#include "OpenMeshSkinned/Solver/Refit.hh"

#include "OpenMeshSkinned/Deform/ExampleFrames.hh"
#include "OpenMeshSkinned/Eval/SurfaceDistance.hh"
#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Solver/FitSamples.hh"
#include "OpenMeshSkinned/Solver/RefitWeights.hh"
#include "OpenMeshSkinned/Solver/Threads.hh"

#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace OpenMeshSkinned {

namespace {

// Posed position of a vertex as an affine function of its rest position: y = A x + c.
struct AffineVertex {
  Eigen::Matrix3d A;
  Eigen::Vector3d c;
};

std::vector<AffineVertex> affine_skin(const SkinnedMesh& mesh, const Pose& pose) {
  const auto h = influences_handle(mesh);
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  const bool morph = !pose.morph_weights.empty() && morph_deltas_handle(mesh, hd);
  std::vector<AffineVertex> out(mesh.n_vertices());
  for (auto vh : mesh.vertices()) {
    const Influences& w = mesh.property(h, vh);
    const Eigen::Vector3d t = skin_point(Eigen::Vector3d::Zero(), w, pose);
    AffineVertex& a = out[vh.idx()];
    for (int i = 0; i < 3; ++i) a.A.col(i) = skin_point(Eigen::Vector3d::Unit(i), w, pose) - t;
    const Eigen::Vector3d d = morph ? apply_morph(Eigen::Vector3d::Zero(), mesh.property(hd, vh), pose.morph_weights)
                                    : Eigen::Vector3d::Zero();
    a.c = a.A * d + t;
  }
  return out;
}

// The blocks of J^T J that residuals can fill: a residual touches one vertex or the corners of one LOD
// triangle, so every vertex pairs with itself and its one-ring. Kept as sorted rows (a hash map per block
// was a third of the fit).
struct BlockPattern {
  std::vector<int> start, cols;
  explicit BlockPattern(const SkinnedMesh& lod) {
    start.assign(lod.n_vertices() + 1, 0);
    std::vector<int> row;
    for (auto vh : lod.vertices()) {
      row.assign(1, vh.idx());
      for (auto w : lod.vv_range(vh)) row.push_back(w.idx());
      std::sort(row.begin(), row.end());
      cols.insert(cols.end(), row.begin(), row.end());
      start[vh.idx() + 1] = static_cast<int>(cols.size());
    }
  }
  int find(int i, int j) const {
    return static_cast<int>(std::lower_bound(cols.begin() + start[i], cols.begin() + start[i + 1], j) - cols.begin());
  }
};

// Accumulates the normal equations of residuals sum_k b_k (A_k x_k + c_k) - target, 3x3 block by block.
struct Normal {
  const BlockPattern& pattern;
  std::vector<Eigen::Matrix3d> blocks;
  Eigen::VectorXd rhs;
  double sum_sq = 0.0;
  size_t n = 0;
  Normal(const BlockPattern& p, size_t nv)
      : pattern(p), blocks(p.cols.size(), Eigen::Matrix3d::Zero()), rhs(Eigen::VectorXd::Zero(long(3 * nv))) {}
  /// A residual measured along \p normal (unit) in full and across it with weight \p tangential; a zero
  /// normal or a tangential weight of 1 measures it in full every way. Counted in sum_sq and n.
  void add(const int* v, const double* b, int m, const std::vector<AffineVertex>& av,
           const std::vector<Eigen::Vector3d>& x, const Eigen::Vector3d& target,
           const Eigen::Vector3d& normal = Eigen::Vector3d::Zero(), double tangential = 1.0) {
    sum_sq += accumulate(v, b, m, av, x, target, normal, tangential, 1.0).squaredNorm();
    ++n;
  }
  /// As add(), its square weighted by \p weight, and not counted in sum_sq and n (a residual of another kind).
  void add_weighted(const int* v, const double* b, int m, const std::vector<AffineVertex>& av,
                    const std::vector<Eigen::Vector3d>& x, const Eigen::Vector3d& target, const Eigen::Vector3d& normal,
                    double tangential, double weight) {
    accumulate(v, b, m, av, x, target, normal, tangential, weight);
  }
  Eigen::Vector3d accumulate(const int* v, const double* b, int m, const std::vector<AffineVertex>& av,
                             const std::vector<Eigen::Vector3d>& x, const Eigen::Vector3d& target,
                             const Eigen::Vector3d& normal, double tangential, double weight) {
    Eigen::Vector3d r = -target;
    for (int i = 0; i < m; ++i) r += b[i] * (av[v[i]].A * x[v[i]] + av[v[i]].c);
    const Eigen::Matrix3d W = residual_metric(normal, tangential, weight);
    // J_i = b_i A_i; the step solves J^T W J dx = -J^T W r.
    Eigen::Matrix3d J[3];
    for (int i = 0; i < m; ++i) J[i] = b[i] * av[v[i]].A;
    const Eigen::Vector3d Wr = W * r;
    for (int i = 0; i < m; ++i) {
      rhs.segment<3>(3 * v[i]) -= J[i].transpose() * Wr;
      const Eigen::Matrix3d JtW = J[i].transpose() * W;
      for (int j = 0; j < m; ++j) blocks[pattern.find(v[i], v[j])] += JtW * J[j];
    }
    return r;
  }
  void add_diagonal(size_t v, double lambda) {
    blocks[pattern.find(int(v), int(v))] += lambda * Eigen::Matrix3d::Identity();
  }
  Eigen::SparseMatrix<double> matrix(size_t nv) const {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(blocks.size() * 9);
    for (size_t i = 0; i < nv; ++i)
      for (int k = pattern.start[i]; k < pattern.start[i + 1]; ++k)
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) t.emplace_back(long(3 * i) + a, 3L * pattern.cols[k] + c, blocks[k](a, c));
    Eigen::SparseMatrix<double> M(long(3 * nv), long(3 * nv));
    M.setFromTriplets(t.begin(), t.end());
    return M;
  }
};

// Where a point of the posed original lies on the posed LOD: a triangle and barycentric weights.
struct Hit {
  int id = -1;  // the triangle's index in the posed LOD's soup (the same every round: the topology is fixed)
  std::array<int, 3> tri;
  Eigen::Vector3d bary;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // across the posed LOD there (unit; zero: no direction)
};

// Runs work(t, j) for j in [0, n) on up to \p threads threads, t the thread's number; each j is done by
// exactly one of them.
template <typename Work>
void for_each_pose(size_t n, int threads, Work work) {
  std::atomic<size_t> next{0};
  run_on_threads(std::min<int>(threads, int(n)), [&](int t) {
    for (size_t j = next++; j < n; j = next++) work(t, j);
  });
}

// The faces that turn by more than 90 degrees, in some pose, between \p a and \p b (posed positions).
std::vector<SkinnedMesh::FaceHandle> folding_faces(const SkinnedMesh& mesh,
                                                   const std::vector<std::vector<Eigen::Vector3d>>& a,
                                                   const std::vector<std::vector<Eigen::Vector3d>>& b) {
  std::vector<char> folded(mesh.n_faces(), 0);
  for (size_t j = 0; j < a.size(); ++j) {
    const auto na = skin_face_normals(mesh, a[j]), nb = skin_face_normals(mesh, b[j]);
    for (auto fh : mesh.faces())
      if (na[fh.idx()].squaredNorm() > 0.0 && na[fh.idx()].dot(nb[fh.idx()]) <= 0.0) folded[fh.idx()] = 1;
  }
  std::vector<SkinnedMesh::FaceHandle> out;
  for (auto fh : mesh.faces())
    if (folded[fh.idx()]) out.push_back(fh);
  return out;
}

// What every round fits to, per pose: the original's samples posed, and the point of the posed original
// each LOD vertex must stay on.
struct PoseTargets {
  std::vector<size_t> samples;
  // The samples in the leaf order of the original's search hierarchy where they lie (set by the thread that
  // took the first pose): taken in this order, each query can start from the triangle the one before it hit,
  // which lies near its answer, and consecutive queries reach into the same boxes. Any order gives the same hits.
  std::vector<uint32_t> order;
  std::vector<std::vector<Eigen::Vector3d>> sample_at;  // pose -> sample -> posed point
  std::vector<std::vector<Eigen::Vector3d>> target;     // pose -> LOD vertex -> point on the posed original
  std::vector<std::vector<char>> has_target;
  // Points of the LOD's faces (fixed barycentric places) and where each lies on the posed original.
  struct FaceSample {
    std::array<int, 3> v;
    Eigen::Vector3d b;
    double weight;
  };
  std::vector<FaceSample> face_samples;
  std::vector<std::vector<Eigen::Vector3d>> face_target, face_normal;  // pose -> face sample -> point, normal
  std::vector<std::vector<char>> has_face_target;
};

// The permutation of \p samples (vertex indices below \p n_vertices, then triangle indices offset by it)
// that sorts them by the rank in \p surface's hierarchy of the triangle each lies on (for a vertex, the first that uses
// it).
std::vector<uint32_t> leaf_order(const MeasuredSurface& surface, size_t n_vertices,
                                 const std::vector<std::array<int, 3>>& triangles, const std::vector<size_t>& samples) {
  std::vector<int> first(n_vertices, -1);
  for (size_t t = triangles.size(); t-- > 0;)
    for (int v : triangles[t]) first[v] = int(t);
  std::vector<std::pair<int, uint32_t>> keyed(samples.size());
  for (size_t k = 0; k < samples.size(); ++k) {
    const size_t i = samples[k];
    keyed[k] = {surface.rank(i < n_vertices ? first[i] : int(i - n_vertices)), uint32_t(k)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> order(keyed.size());
  for (size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
  return order;
}

// Fixed places on the LOD's faces, drawn to the original as its vertices are: the held-out measure is
// symmetric, and a coarse LOD's face can leave the original between vertices that lie on it (its worst
// distance is mostly there). The centroids of each face split into split x split triangles (fewer where
// they would be more than \p max_samples), weighted by the face's area so that all of them weigh \p weight
// times \p n_original samples of the original. None on a LOD of more than \p max_samples faces: its
// vertices' targets hold it, and samples on some of its faces only (measured) fitted worse than none.
std::vector<PoseTargets::FaceSample> face_samples(const SkinnedMesh& lod, int split, double weight, size_t n_original,
                                                  size_t max_samples) {
  std::vector<PoseTargets::FaceSample> out;
  if (!(weight > 0.0) || lod.n_faces() == 0 || lod.n_faces() > max_samples) return out;
  while (split > 1 && lod.n_faces() * size_t(split * split) > max_samples) --split;
  std::vector<Eigen::Vector3d> places;
  for (int i = 0; i < split; ++i)
    for (int k = 0; i + k < split; ++k) {
      places.emplace_back((i + 1.0 / 3) / split, (k + 1.0 / 3) / split, 1.0 - (i + k + 2.0 / 3) / split);
      if (i + k + 1 < split)
        places.emplace_back((i + 2.0 / 3) / split, (k + 2.0 / 3) / split, 1.0 - (i + k + 4.0 / 3) / split);
    }
  double total = 0.0;
  for (auto fh : lod.faces()) total += lod.calc_face_area(fh);
  if (!(total > 0.0)) return out;
  const double per_area = weight * double(n_original) / total / double(places.size());
  for (auto fh : lod.faces()) {
    const double w = per_area * lod.calc_face_area(fh);
    if (!(w > 0.0)) continue;
    std::array<int, 3> v;
    int i = 0;
    for (auto vh : lod.fv_range(fh)) v[i++] = vh.idx();
    for (const auto& b : places) out.push_back({v, b, w});
  }
  return out;
}

// Per pose, on threads taking poses in turn (each thread one search hierarchy, posed again pose by pose):
// the samples posed, and where each LOD vertex lies on the posed original, found once from the
// decimated LOD; the LOD must not leave those points. (Found in the rest shape instead, a vertex where
// two parts touch at rest, a helmet on a head, could be tied to the wrong one.)
void find_pose_targets(const SkinnedMesh& lod, const SkinnedMesh& original, const std::vector<Pose>& poses,
                       const std::vector<std::array<int, 3>>& triangles, int threads, PoseTargets& pt) {
  const size_t nv = lod.n_vertices(), np = poses.size();
  pt.target.assign(np, std::vector<Eigen::Vector3d>(nv));
  pt.has_target.assign(np, std::vector<char>(nv, 0));
  pt.sample_at.assign(np, {});
  pt.face_target.assign(np, {});
  pt.face_normal.assign(np, {});
  pt.has_face_target.assign(np, {});
  std::vector<std::unique_ptr<MeasuredSurface>> surfaces(std::max(1, threads));
  // Each thread's last answer per vertex starts its next pose's search (a vertex moves little from pose to
  // pose; the nearest point does not depend on the hint); the previous vertex's starts the first.
  std::vector<std::vector<int>> hints(std::max(1, threads), std::vector<int>(nv, -1));
  for_each_pose(np, threads, [&](int t, size_t j) {
    TriangleSoup posed;
    posed.points = skin_positions(original, poses[j]);
    posed.triangles = triangles;
    auto& sp = pt.sample_at[j];
    sp.reserve(pt.samples.size());
    for (size_t i : pt.samples) {
      sp.push_back(sample_point(posed.points, triangles, original.n_vertices(), i));
    }
    const MeasuredSurface& surface = posed_surface(surfaces[t], posed, 0, 1);
    if (j == 0) pt.order = leaf_order(surface, original.n_vertices(), triangles, pt.samples);
    const std::vector<Eigen::Vector3d> y = skin_positions(lod, poses[j]);
    int previous = -1;
    for (auto vh : lod.vertices()) {
      int tri = -1;
      int& hint = hints[t][vh.idx()];
      surface.distance(y[vh.idx()], tri, hint >= 0 ? hint : previous);
      hint = tri;
      if (tri < 0) continue;
      previous = tri;
      const auto& T = posed.triangles[tri];
      const Eigen::Vector3d corners[3] = {posed.points[T[0]], posed.points[T[1]], posed.points[T[2]]};
      Eigen::Vector3d bary;
      closest_barycentric(corners, y[vh.idx()], bary);
      pt.target[j][vh.idx()] = bary[0] * corners[0] + bary[1] * corners[1] + bary[2] * corners[2];
      pt.has_target[j][vh.idx()] = 1;
    }
    const size_t nfs = pt.face_samples.size();
    pt.face_target[j].resize(nfs);
    pt.face_normal[j].resize(nfs);
    pt.has_face_target[j].assign(nfs, 0);
    for (size_t k = 0; k < nfs; ++k) {
      const auto& fs = pt.face_samples[k];
      const Eigen::Vector3d q = fs.b[0] * y[fs.v[0]] + fs.b[1] * y[fs.v[1]] + fs.b[2] * y[fs.v[2]];
      // Its nearest corner's triangle, found just above, lies near its answer.
      int corner = 0;
      for (int c = 1; c < 3; ++c)
        if (fs.b[c] > fs.b[corner]) corner = c;
      const int near = hints[t][fs.v[corner]];
      int tri = -1;
      surface.distance(q, tri, near >= 0 ? near : previous);
      if (tri < 0) continue;
      previous = tri;
      const auto& T = posed.triangles[tri];
      const Eigen::Vector3d corners[3] = {posed.points[T[0]], posed.points[T[1]], posed.points[T[2]]};
      Eigen::Vector3d bary;
      closest_barycentric(corners, q, bary);
      pt.face_target[j][k] = bary[0] * corners[0] + bary[1] * corners[1] + bary[2] * corners[2];
      const Eigen::Vector3d fn = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
      pt.face_normal[j][k] = fn.norm() > 0.0 ? Eigen::Vector3d(fn.normalized()) : Eigen::Vector3d::Zero();
      pt.has_face_target[j][k] = 1;
    }
  });
}

// The original's samples onto the posed LOD, pose by pose on the threads.
void project_samples(const SkinnedMesh& lod, const std::vector<Pose>& poses, const PoseTargets& pt, int threads,
                     std::vector<std::vector<Hit>>& hits) {
  std::vector<std::unique_ptr<MeasuredSurface>> surfaces(std::max(1, threads));
  for_each_pose(poses.size(), threads, [&](int t, size_t j) {
    const TriangleSoup lsoup = posed_soup(lod, poses[j]);
    // After the first round, last round's triangle starts each search (the LOD moved little since); in the
    // first, the one the sample before it hit.
    const MeasuredSurface& lsurf = posed_surface(surfaces[t], lsoup, 0, 1);
    hits[j].resize(pt.samples.size(), Hit{-1, {-1, -1, -1}, Eigen::Vector3d::Zero()});
    int previous = -1;
    for (uint32_t s : pt.order) {
      Hit& h = hits[j][s];
      int tri = -1;
      lsurf.distance(pt.sample_at[j][s], tri, h.id >= 0 ? h.id : previous);
      if (tri >= 0) previous = tri;
      h.id = tri;
      h.tri = {-1, -1, -1};
      if (tri < 0) continue;
      h.tri = lsoup.triangles[tri];
      const Eigen::Vector3d corners[3] = {lsoup.points[h.tri[0]], lsoup.points[h.tri[1]], lsoup.points[h.tri[2]]};
      closest_barycentric(corners, pt.sample_at[j][s], h.bary);
      // The direction the sample lies in from its nearest point: the face's normal when that point is inside
      // the face, and across an edge or corner it turns with the sample from one face's normal to the next,
      // so the fit does not jump where the nearest point crosses an edge.
      const Eigen::Vector3d nearest = h.bary[0] * corners[0] + h.bary[1] * corners[1] + h.bary[2] * corners[2];
      const Eigen::Vector3d off = pt.sample_at[j][s] - nearest;
      const Eigen::Vector3d fn = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
      // A sample within rounding of an edge has no direction of its own: the face's is as good.
      const double rounding = 1e-9 * std::max({(corners[1] - corners[0]).norm(), (corners[2] - corners[1]).norm(),
                                               (corners[0] - corners[2]).norm()});
      if (h.bary.minCoeff() <= 0.0 && off.norm() > rounding)
        h.normal = off.normalized();
      else
        h.normal = fn.norm() > 0.0 ? Eigen::Vector3d(fn.normalized()) : Eigen::Vector3d::Zero();
    }
  });
}

// Every residual of the fit, pose by pose in pose order (so that sums over them do not depend on the thread
// count): each original sample to its nearest point on the posed LOD, each face sample and each LOD vertex to
// its point on the posed original. \p visit(pose, corners, bary, m, target, normal, weight, counted): a sample's
// nearest point on the LOD is last round's answer, so its residual is measured along Hit::normal (the fit's
// tangential weight across it); the face samples are residuals of another kind (not counted in the report).
template <typename Visit>
void for_each_residual(const SkinnedMesh& lod, const PoseTargets& pt, const std::vector<std::vector<Hit>>& hits,
                       Visit visit) {
  static const double one = 1.0;
  const Eigen::Vector3d none = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < hits.size(); ++j) {
    for (size_t s = 0; s < pt.samples.size(); ++s)
      if (hits[j][s].tri[0] >= 0)
        visit(j, hits[j][s].tri.data(), hits[j][s].bary.data(), 3, pt.sample_at[j][s], hits[j][s].normal, 1.0, true);
    for (size_t k = 0; k < pt.face_samples.size(); ++k)
      if (pt.has_face_target[j][k]) {
        const auto& fs = pt.face_samples[k];
        visit(j, fs.v.data(), fs.b.data(), 3, pt.face_target[j][k], pt.face_normal[j][k], fs.weight, false);
      }
    for (auto vh : lod.vertices()) {
      const int v = vh.idx();
      if (pt.has_target[j][v]) visit(j, &v, &one, 1, pt.target[j][v], none, 1.0, true);
    }
  }
}

// The residuals summed into the normal equations of the rest positions.
void add_residuals(const SkinnedMesh& lod, const PoseTargets& pt, const std::vector<std::vector<Hit>>& hits,
                   const std::vector<std::vector<AffineVertex>>& affine, const std::vector<Eigen::Vector3d>& x,
                   double tangential, Normal& ne) {
  for_each_residual(lod, pt, hits,
                    [&](size_t j, const int* v, const double* b, int m, const Eigen::Vector3d& target,
                        const Eigen::Vector3d& normal, double weight, bool counted) {
                      if (counted)
                        ne.add(v, b, m, affine[j], x, target, normal, tangential);
                      else
                        ne.add_weighted(v, b, m, affine[j], x, target, normal, tangential, weight);
                    });
}

// Halve the step until no face folds in any pose. A sliver turns over at any step: if one still folds
// at the smallest, its corners stay where they are and the others try again, so that one face does
// not hold the whole LOD back. False, with the LOD put back at \p x, when no step is left.
bool take_step(SkinnedMesh& lod, const std::vector<Pose>& poses,
               const std::vector<std::vector<Eigen::Vector3d>>& posed_initial, const std::vector<Eigen::Vector3d>& x,
               const Eigen::VectorXd& dx) {
  Eigen::VectorXd step_dir = dx;
  bool moved = false;
  for (int pinning = 0; pinning < 4 && !moved; ++pinning) {
    double step = 1.0;
    std::vector<SkinnedMesh::FaceHandle> folded;
    for (int tries = 0; tries < 6 && !moved; ++tries, step *= 0.5) {
      for (auto vh : lod.vertices()) {
        const int v = vh.idx();
        const Eigen::Vector3d p = x[v] + step * step_dir.segment<3>(3 * v);
        lod.set_point(vh, SkinnedMesh::Point(p.x(), p.y(), p.z()));
      }
      std::vector<std::vector<Eigen::Vector3d>> posed_after;
      for (const Pose& p : poses) posed_after.push_back(skin_positions(lod, p));
      folded = folding_faces(lod, posed_initial, posed_after);
      moved = folded.empty();
    }
    for (auto fh : folded)
      for (auto vh : lod.fv_range(fh)) step_dir.segment<3>(3 * vh.idx()).setZero();
  }
  if (!moved)
    for (auto vh : lod.vertices())
      lod.set_point(vh, SkinnedMesh::Point(x[vh.idx()].x(), x[vh.idx()].y(), x[vh.idx()].z()));
  return moved;
}

// J^T J dx = rhs. Factorizing costs time and memory that grow faster than the mesh (fill-in); the pull
// toward the decimated positions keeps the system well conditioned, so conjugate gradients converge in a few
// iterations where the mesh is large. The factorization remains the answer when they do not.
bool solve_step(const Eigen::SparseMatrix<double>& JtJ, const Eigen::VectorXd& rhs, bool iterative,
                Eigen::VectorXd& dx) {
  if (iterative) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg(JtJ);
    cg.setTolerance(1e-10);
    cg.setMaxIterations(200);
    dx = cg.solve(rhs);
    if (cg.info() == Eigen::Success && dx.allFinite()) return true;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(JtJ);
  if (solver.info() != Eigen::Success) return false;
  dx = solver.solve(rhs);
  return solver.info() == Eigen::Success && dx.allFinite();
}

// The fit's residuals as the skin step takes them.
std::vector<WeightResidual> weight_residuals(const SkinnedMesh& lod, const PoseTargets& pt,
                                             const std::vector<std::vector<Hit>>& hits) {
  std::vector<WeightResidual> out;
  for_each_residual(lod, pt, hits,
                    [&](size_t j, const int* v, const double* b, int m, const Eigen::Vector3d& target,
                        const Eigen::Vector3d& normal, double weight, bool) {
                      WeightResidual r;
                      for (int i = 0; i < m; ++i) r.v[i] = v[i], r.bary[i] = b[i];
                      r.target = target;
                      r.normal = normal;
                      r.weight = weight;
                      r.corners = m;
                      r.pose = int(j);
                      out.push_back(r);
                    });
  return out;
}

// The skin step (RefitWeights.hh) on the residuals where the positions' rounds left the LOD. A face that
// then folds in some pose gets its corners' weights back (all of them, if folds remain).
void fit_weights(SkinnedMesh& lod, const std::vector<Pose>& poses, const PoseTargets& pt,
                 std::vector<std::vector<Hit>>& hits, const RefitSettings& settings, int threads,
                 const std::vector<std::vector<Eigen::Vector3d>>& posed_initial) {
  const auto h = influences_handle(lod);
  std::vector<Influences> before;
  for (auto vh : lod.vertices()) before.push_back(lod.property(h, vh));
  project_samples(lod, poses, pt, threads, hits);
  WeightRefitSettings ws;
  ws.max_influences = settings.max_influences;
  if (ws.max_influences == 0) {
    ws.max_influences = 1;
    for (const Influences& inf : before) ws.max_influences = std::max(ws.max_influences, inf.size());
  }
  ws.tangential_weight = settings.tangential_weight;
  if (refit_weights(lod, poses, weight_residuals(lod, pt, hits), ws) == 0) return;
  for (int tries = 0; tries < 5; ++tries) {
    std::vector<std::vector<Eigen::Vector3d>> posed_after;
    for (const Pose& p : poses) posed_after.push_back(skin_positions(lod, p));
    const auto folded = folding_faces(lod, posed_initial, posed_after);
    if (folded.empty()) return;
    if (tries == 4)
      for (auto vh : lod.vertices()) lod.property(h, vh) = before[vh.idx()];
    for (auto fh : folded)
      for (auto vh : lod.fv_range(fh)) lod.property(h, vh) = before[vh.idx()];
  }
}

}  // namespace

RefitReport refit_positions(SkinnedMesh& lod, const SkinnedMesh& original, const std::vector<Pose>& poses,
                            const RefitSettings& settings) {
  RefitReport report;
  if (!(settings.tangential_weight > 0.0 && settings.tangential_weight <= 1.0))
    throw std::invalid_argument("refit: the tangential weight must be in (0, 1]");
  if (!(settings.face_weight >= 0.0 && std::isfinite(settings.face_weight)))
    throw std::invalid_argument("refit: the face weight must be a finite number, 0 or more");
  if (settings.face_split < 1) throw std::invalid_argument("refit: the face split must be 1 or more");
  if (settings.max_influences < 0 || settings.max_influences > Influences::kCapacity)
    throw std::invalid_argument("refit: the cap on influences must be 0 (the LOD's own) to 8");
  if (poses.empty() || lod.n_faces() == 0) return report;
  const size_t nv = lod.n_vertices(), np = poses.size();
  const int threads = std::max(1, settings.threads);
  const std::vector<std::array<int, 3>> triangles = mesh_triangles(original);
  PoseTargets pt;
  pt.samples = strided_samples(original, triangles.size(), settings.max_samples);
  pt.face_samples =
      face_samples(lod, settings.face_split, settings.face_weight, pt.samples.size(), settings.max_samples);
  find_pose_targets(lod, original, poses, triangles, threads, pt);
  const std::vector<Eigen::Vector3d> x0 = rest_points(lod);
  // Skins and morph offsets do not change: each pose's affine maps serve every round.
  std::vector<std::vector<AffineVertex>> affine;
  for (const Pose& p : poses) affine.push_back(affine_skin(lod, p));
  // Folds are judged against the decimated LOD, not round by round: small turns must not add up.
  std::vector<std::vector<Eigen::Vector3d>> posed_initial;
  for (const Pose& p : poses) posed_initial.push_back(skin_positions(lod, p));
  const BlockPattern pattern(lod);
  std::vector<std::vector<Hit>> hits(np);
  for (int round = 0; round < settings.rounds; ++round) {
    std::vector<Eigen::Vector3d> x(nv);
    for (auto vh : lod.vertices()) x[vh.idx()] = to_eigen(lod.point(vh));
    project_samples(lod, poses, pt, threads, hits);
    Normal ne(pattern, nv);
    add_residuals(lod, pt, hits, affine, x, settings.tangential_weight, ne);
    const double rms = std::sqrt(ne.sum_sq / std::max<size_t>(1, ne.n));
    if (round == 0) report.before = rms;
    report.after = rms;
    // The pull toward the decimated positions, scaled like one residual per pose.
    const double lambda = settings.regularization * double(poses.size());
    for (size_t v = 0; v < nv; ++v) {
      ne.add_diagonal(v, lambda);
      ne.rhs.segment<3>(long(3 * v)) -= lambda * (x[v] - x0[v]);
    }
    const Eigen::SparseMatrix<double> JtJ = ne.matrix(nv);
    Eigen::VectorXd dx;
    if (!solve_step(JtJ, ne.rhs, nv > settings.direct_max_vertices, dx)) break;
    if (!take_step(lod, poses, posed_initial, x, dx)) break;
    ++report.rounds;
  }
  if (settings.fit_weights) fit_weights(lod, poses, pt, hits, settings, threads, posed_initial);
  return report;
}

}  // namespace OpenMeshSkinned
