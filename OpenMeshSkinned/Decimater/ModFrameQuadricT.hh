#pragma once
/** \file ModFrameQuadricT.hh */

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include "OpenMeshSkinned/Collapse/FoldOver.hh"
#include "OpenMeshSkinned/Collapse/MorphTransferT.hh"
#include "OpenMeshSkinned/Collapse/UvTransferT.hh"
#include "OpenMeshSkinned/Deform/ExampleFrames.hh"
#include "OpenMeshSkinned/Solver/AreaPrice.hh"
#include "OpenMeshSkinned/Solver/VertexQuadrics.hh"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace OpenMeshSkinned {

/** Priority module: the error of a collapse summed over the example poses, each pose with its own
 *  Garland-Heckbert quadrics (area-weighted planes of the posed faces) evaluated on the merged vertex's
 *  trajectory. It is the skinned quadric's idea without weights to solve, and it needs no skeleton: the
 *  poses may be morph-target frames (a mesh animated without a skeleton) or skinned poses, morph offsets
 *  and skin applied.
 *
 *  As in the skinned quadric, a border edge adds, in every pose, a plane through it perpendicular to its
 *  face, so that open borders do not shrink away.
 *
 *  Placement (set_placement(), on by default): the merged vertex slides along the edge, its trajectory the
 *  same blend of the endpoints' trajectories, (1 - t) a_f + t b_f in every frame f; the error is then a
 *  parabola in t, minimised in closed form over [0, 1]. The vertex's rest position, morph offsets and UVs
 *  are interpolated to match (MorphTransferT, UvTransferT). Two endpoints with different skins blend
 *  non-linearly under skinning, so there t is 0 or 1 (the survivor takes one endpoint's position and
 *  skin), and a boundary vertex stays put (the faces' planes do not see a boundary pulled inwards). With
 *  placement off it is a plain halfedge collapse (the survivor keeps its own trajectory).
 *
 *  Because the placement is decided here, the fold-over check in every example pose is here too
 *  (set_max_fold_angle(), default 90 degrees; ModFrameFoldOverT is the check for endpoint modules): a
 *  collapse that turns a face around it by more than the angle in some pose, or leaves it without area
 *  there, is illegal. The verdict on a placement depends on both endpoints' rings: LazyDecimaterT asks at the
 *  collapse, so it is always fresh there; under DecimaterT a placement found folding at the collapse falls
 *  back to the endpoint (stale_placements() counts those, forced_folds() those whose endpoint folds too,
 *  which DecimaterT then makes anyway).
 *
 *  Memory: one quadric (10 doubles) and one position per vertex and example pose.
 *
 *  \code
 *  OpenMeshSkinned::ModFrameQuadricT<Mesh>::Handle hq;
 *  dec.add(hq);   // after setting example_poses(mesh)
 *  \endcode
 */
template <typename MeshT>
class ModFrameQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
public:
  DECIMATING_MODULE(ModFrameQuadricT, MeshT, FrameQuadric);

  explicit ModFrameQuadricT(MeshT& mesh) : Base(mesh, false), uv_(mesh), morph_(mesh) {}

  /// Collapses whose priority exceeds \p err (the energy, or energy over a power of the area with
  /// set_area_exponent()) are refused. Default: none.
  void set_max_err(double err) { max_err_ = err; }
  double max_err() const { return max_err_; }

  /** Prices collapses by energy / area^\p a, the area being what the endpoints' quadrics stand for (their
   *  summed planes' trace, averaged over the frames), as ModSkinnedQuadricT::set_area_exponent() does: 0 is
   *  the energy (the default), 1 a mean squared distance. Throws std::invalid_argument outside [0, 1]. */
  void set_area_exponent(double a) {
    check_area_exponent("ModFrameQuadricT", a);
    area_exponent_ = a;
  }
  double area_exponent() const { return area_exponent_; }

  /** Collapses standing for less than area \p A are priced per area, scaled so that the two prices meet at
   *  A (ModSkinnedQuadricT::set_area_floor()). Throws std::invalid_argument if negative or not finite.
   *  Default 0: none. */
  void set_area_floor(double A) {
    check_area_floor("ModFrameQuadricT", A);
    area_floor_ = A;
  }
  double area_floor() const { return area_floor_; }

  void set_placement(bool on) { placement_ = on; }
  bool placement() const { return placement_; }
  void set_max_fold_angle(double deg) { min_cos_ = std::cos(deg * M_PI / 180.0); }
  double max_fold_angle() const { return std::acos(min_cos_) * 180.0 / M_PI; }
  /// Collapses whose placement folded by the time they were made and fell back to the endpoint (only under
  /// a driver that does not ask at the collapse, such as DecimaterT).
  size_t stale_placements() const { return stale_placements_; }
  /// Of those, the ones whose endpoint folded too: DecimaterT made them anyway.
  size_t forced_folds() const { return forced_folds_; }

  void initialize() override {
    const MeshT& mesh = Base::mesh();
    frames_ = example_frame_points(mesh);
    poses_ = example_poses(mesh);
    P_ = frames_.size();
    h_inf_ = influences_handle(mesh);
    q_.assign(mesh.n_vertices() * P_, PoseQuadric{});
    accumulate_quadrics(
        mesh, int(P_), [this](typename MeshT::VertexHandle v, int t) { return frames_[t][v.idx()]; },
        [this](typename MeshT::VertexHandle v, int t) -> PoseQuadric& { return q_[v.idx() * P_ + t]; });
    uv_.prepare();
  }

  float collapse_priority(const CollapseInfo& ci) override {
    Placement pl;
    const double e = price(std::max(0.0, place(ci, pl)));
    if (e > max_err_ * Base::error_tolerance_factor_ || folds(ci, pl)) return float(Base::ILLEGAL_COLLAPSE);
    return float(std::min<double>(e, FLT_MAX / 2));
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    const size_t v0 = ci.v0.idx(), v1 = ci.v1.idx();
    place(ci, pending_);
    // Under OpenMesh's DecimaterT the verdict on a placement can be stale: it depends on both endpoints'
    // rings, and DecimaterT re-prices only the ring of each collapse's survivor. The endpoint's verdict
    // (v0's faces alone) cannot be, so a placement that folds by now falls back to it.
    if (pending_.moved && folds(ci, pending_)) {
      pending_.moved = false;
      ++stale_placements_;
      if (folds(ci, pending_)) ++forced_folds_;
    }
    for (size_t f = 0; f < P_; ++f) q_[v1 * P_ + f] += q_[v0 * P_ + f];
    if (!pending_.moved) return;
    uv_.record(ci.v0, ci.v1);
    morph_.record(ci.v0, ci.v1);
    for (size_t f = 0; f < P_; ++f) frames_[f][v1] = pending_.trajectory[f];
    if (pending_.v0_skin) Base::mesh().property(h_inf_, ci.v1) = Base::mesh().property(h_inf_, ci.v0);
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    if (!pending_.moved) return;
    const Eigen::Vector3d& p = pending_.rest;
    Base::mesh().set_point(ci.v1, typename MeshT::Point(p.x(), p.y(), p.z()));
    uv_.apply(ci.v1);
    morph_.apply(ci.v1);
  }

private:
  // Where the merged vertex goes: v1 as it is (moved = false), or a rest position with the trajectory it
  // then has in every example pose.
  struct Placement {
    bool moved = false;
    bool v0_skin = false;  // the survivor takes v0's skin (and trajectory)
    Eigen::Vector3d rest;
    std::vector<Eigen::Vector3d> trajectory;
  };

  // The priority of an edge whose summed quadrics (sum_) have the least energy \p e.
  double price(double e) const {
    if (area_exponent_ == 0.0) return e;
    double area = 0.0;
    for (size_t f = 0; f < P_; ++f) area += sum_[f].A().trace();
    return area_price(e, area / double(std::max<size_t>(P_, 1)), area_exponent_, area_floor_);
  }

  // Summed quadrics of the edge's endpoints, per pose.
  double energy(const std::vector<PoseQuadric>& q, const std::vector<Eigen::Vector3d>& traj) const {
    double e = 0.0;
    for (size_t f = 0; f < P_; ++f) e += q[f](traj[f]);
    return e;
  }

  // The trajectory of a vertex at rest position \p p with the skin \p w, its morph offsets interpolated as
  // MorphTransferT will: at the closest point of the faces around the collapse.
  void trajectory(const CollapseInfo& ci, const Eigen::Vector3d& p, const Influences& w,
                  std::vector<Eigen::Vector3d>& out) {
    MeshT& mesh = Base::mesh();
    out.resize(P_);
    OpenMesh::VPropHandleT<MorphDeltas> hd;
    const bool morph = morph_deltas_handle(mesh, hd);
    typename MeshT::VertexHandle at[3];
    Eigen::Vector3d bary(1.0, 0.0, 0.0);
    if (morph) {
      double best = HUGE_VAL;
      Eigen::Vector3d b;
      for (auto c : {ci.v0, ci.v1})
        for (auto fh : mesh.vf_range(c)) {
          Eigen::Vector3d t[3];
          typename MeshT::VertexHandle vs[3];
          int k = 0;
          for (auto vh : mesh.fv_range(fh)) vs[k] = vh, t[k++] = to_eigen(mesh.point(vh));
          const double d = closest_barycentric(t, p, b);
          if (d < best) best = d, bary = b, at[0] = vs[0], at[1] = vs[1], at[2] = vs[2];
        }
    }
    for (size_t f = 0; f < P_; ++f) {
      Eigen::Vector3d x = p;
      if (poses_.empty()) {  // no example pose: the rest shape is the only frame
        out[f] = x;
        continue;
      }
      const Pose& pose = poses_[f];
      if (morph && !pose.morph_weights.empty())
        for (int k = 0; k < 3; ++k)
          x += bary[k] * apply_morph(Eigen::Vector3d::Zero(), mesh.property(hd, at[k]), pose.morph_weights);
      out[f] = skin_point(x, w, pose);
    }
  }

  // The least error over the placements allowed; \p out says where.
  double place(const CollapseInfo& ci, Placement& out) {
    const size_t v0 = ci.v0.idx(), v1 = ci.v1.idx();
    MeshT& mesh = Base::mesh();
    out.moved = out.v0_skin = false;
    sum_.resize(P_);
    traj_a_.resize(P_);
    traj_b_.resize(P_);
    for (size_t f = 0; f < P_; ++f) {
      sum_[f] = q_[v0 * P_ + f];
      sum_[f] += q_[v1 * P_ + f];
      traj_a_[f] = frames_[f][v0];
      traj_b_[f] = frames_[f][v1];
    }
    double best = energy(sum_, traj_b_);
    // A boundary vertex stays where it is: the planes of the faces cannot see a boundary pulled inwards.
    if (!placement_ || mesh.is_boundary(ci.v0) || mesh.is_boundary(ci.v1)) return best;
    const Eigen::Vector3d ra = to_eigen(mesh.point(ci.v0)), rb = to_eigen(mesh.point(ci.v1));
    const double e0 = energy(sum_, traj_a_);
    auto take = [&](double e, const Eigen::Vector3d& rest, const std::vector<Eigen::Vector3d>& traj, bool v0_skin) {
      if (!(e < best)) return;
      best = e;
      out.moved = true;
      out.v0_skin = v0_skin;
      out.rest = rest;
      out.trajectory = traj;
    };
    if (mesh.property(h_inf_, ci.v0) != mesh.property(h_inf_, ci.v1)) {
      take(e0, ra, traj_a_, true);
      return best;
    }
    take(e0, ra, traj_a_, false);
    const Influences& w = mesh.property(h_inf_, ci.v1);
    // Along the edge the trajectory is the blend of the endpoints' (skinning is linear for one skin):
    // E(t) = e0 + beta t + g t^2 through three samples.
    const double eh = energy(sum_, blend_all(0.5)), e1 = energy(sum_, traj_b_);
    const double g = 2.0 * (e1 - 2.0 * eh + e0), beta = e1 - e0 - g;
    if (g > 0.0) {
      const double ts = -beta / (2.0 * g);
      if (ts > 0.0 && ts < 1.0) take(e0 + beta * ts + g * ts * ts, (1.0 - ts) * ra + ts * rb, blend_all(ts), false);
    }
    // Off the edge: the point the poses' quadrics want if the vertex moved like the edge's middle, then
    // judged on the trajectory it really gets.
    PoseQuadric shifted;
    for (size_t f = 0; f < P_; ++f) {
      const Eigen::Vector3d d = 0.5 * (traj_a_[f] + traj_b_[f]) - 0.5 * (ra + rb);
      const Eigen::Matrix3d A = sum_[f].A();
      const Eigen::Vector3d b = A * d + sum_[f].b();
      const double c = sum_[f](d);
      const double q[10] = {A(0, 0), A(0, 1), A(0, 2), b.x(), A(1, 1), A(1, 2), b.y(), A(2, 2), b.z(), c};
      for (int i = 0; i < 10; ++i) shifted.q[i] += q[i];
    }
    const Eigen::Vector3d p = optimal_point(shifted, ra, rb);
    if ((p - ra).squaredNorm() > 0.0 && (p - rb).squaredNorm() > 0.0) {
      trajectory(ci, p, w, traj_p_);
      take(energy(sum_, traj_p_), p, traj_p_, false);
    }
    return best;
  }

  const std::vector<Eigen::Vector3d>& blend_all(double t) {
    traj_t_.resize(P_);
    for (size_t f = 0; f < P_; ++f) traj_t_[f] = (1.0 - t) * traj_a_[f] + t * traj_b_[f];
    return traj_t_;
  }

  // Whether a face around the collapse (v0's and v1's that survive) turns too far, or loses its area, in
  // some pose when the merged vertex takes the placement's trajectory.
  bool folds(const CollapseInfo& ci, const Placement& pl) {
    surviving_faces(Base::mesh(), ci.v0, ci.v1, ring_);
    if (!pl.moved)  // v1 stays: its own faces do not move
      ring_.erase(std::remove_if(ring_.begin(), ring_.end(), [&](const RingFace& f) { return f[0] != ci.v0.idx(); }),
                  ring_.end());
    const int v1 = ci.v1.idx();
    return folds_in_any_pose(
        ring_, int(P_), [this](int v, int j) { return frames_[j][v]; },
        [&](int j) { return pl.moved ? pl.trajectory[j] : frames_[j][v1]; }, min_cos_);
  }

  double max_err_ = DBL_MAX;
  double area_exponent_ = 0.0, area_floor_ = 0.0;
  bool placement_ = true;
  double min_cos_ = 0.0;
  std::vector<FramePoints> frames_;
  std::vector<RingFace> ring_;
  size_t P_ = 0;
  std::vector<PoseQuadric> q_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  UvTransferT<MeshT> uv_;
  MorphTransferT<MeshT> morph_;
  std::vector<Pose> poses_;
  Placement pending_;
  size_t stale_placements_ = 0, forced_folds_ = 0;
  std::vector<PoseQuadric> sum_;
  std::vector<Eigen::Vector3d> traj_a_, traj_b_, traj_t_, traj_p_;
};

}  // namespace OpenMeshSkinned
