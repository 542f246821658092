#pragma once
/** \file ModDeviationBoundT.hh */

#include "OpenMeshSkinned/Collapse/FoldOver.hh"
#include "OpenMeshSkinned/Decimater/SolverModuleT.hh"
#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace OpenMeshSkinned {

/** Binary module: a bound on the worst deviation, not only a cost. Each vertex of the original, in each
 *  example pose, is handed to a face of the LOD within the limit of it in that pose; a collapse is legal only
 *  when every such point held by a face the collapse changes finds one of the faces that survive it within
 *  the limit, with the merged vertex where the solver will put it. A point is never further from the LOD's
 *  surface than from its face, so bound() — the largest distance ever handed out — is an upper bound, in
 *  every example pose, on the distance from any vertex of the original to the posed LOD (one-sided: the
 *  original's vertices, not every point of its faces).
 *
 *  The quadric prices collapses by their mean error; a thin feature (a finger, an ear's tip) can still be
 *  cut at low cost and show in one pose only. With a limit such a collapse waits, and the decimation stops
 *  early when nothing else is left: the decimater returns fewer collapses than asked.
 *
 *  Under LazyDecimaterT verdicts are asked right before each collapse, so the limit holds. DecimaterT asks
 *  when it prices, and a later collapse nearby can make a verdict stale: the shared solver therefore asks
 *  this module again about the collapses stored near v1 after each collapse and defers those it now
 *  refuses (StaleVerdictsT, as for the fold check); without that the limit slipped (bench/README.md, "Stale
 *  verdicts under DecimaterT"). bound() reports what the decimation really did either way.
 *  The re-check needs a placing priority module (the solver's); with OpenMesh's own it is not made.
 *
 *  Example poses are skinned as the solver poses them (morph offsets are not part of them).
 *
 *  \code
 *  OpenMeshSkinned::ModDeviationBoundT<Mesh>::Handle hb;
 *  dec.add(hb);
 *  dec.module(hb).set_max_deviation(0.01 * diagonal);
 *  \endcode
 */
template <typename MeshT>
class ModDeviationBoundT : public SolverModuleT<MeshT> {
public:
  DECIMATING_MODULE(ModDeviationBoundT, MeshT, DeviationBound);

  explicit ModDeviationBoundT(MeshT& mesh) : SolverModuleT<MeshT>(mesh, true) { this->solver().keep_exact_posed(); }

  /// The limit, in mesh units, on any vertex of the original's distance to the LOD in any example pose.
  void set_max_deviation(double d) {
    max_ = d;
    this->settings_changed();
  }
  double max_deviation() const { return max_; }
  /// The largest distance from a vertex of the original to the face holding it, over the example poses
  /// and every collapse so far (mesh units): an upper bound on the one-sided deviation in those poses.
  double bound() const { return std::sqrt(bound2_); }

  void initialize() override {
    Solver::initialize();
    MeshT& mesh = Base::mesh();
    P_ = this->solver().n_poses();
    // A point is an int (v * P_ + j): a quarter of the memory of 64-bit indices, enough for 2^31 of them.
    if (double(mesh.n_vertices()) * P_ >= double(std::numeric_limits<int>::max()))
      throw std::length_error("ModDeviationBoundT: vertices x example poses exceed 2^31");
    points_.assign(mesh.n_vertices() * size_t(P_), Eigen::Vector3d::Zero());
    held_.assign(mesh.n_faces(), {});
    bound2_ = 0.0;
    // Each vertex starts on one of its own faces, at distance 0 in every pose.
    for (auto vh : mesh.vertices()) {
      auto vf = mesh.vf_begin(vh);
      if (!vf.is_valid()) continue;
      for (int j = 0; j < P_; ++j) {
        points_[size_t(vh.idx()) * P_ + j] = this->solver().posed(vh, j);
        held_[vf->idx()].push_back(vh.idx() * P_ + j);
      }
    }
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    Solver::preprocess_collapse(ci);
    // Every face around v0 and v1 either vanishes or changes: their points are handed out again after.
    pending_.clear();
    for_changed_faces(ci, [&](typename MeshT::FaceHandle fh) {
      auto& h = held_[fh.idx()];
      pending_.insert(pending_.end(), h.begin(), h.end());
      h.clear();
    });
  }

  // The points go to their new faces as soon as the solver has placed v1, before it re-judges the stored
  // verdicts near v1 (under DecimaterT), which must see them where they are.
  void collapse_applied(const CollapseInfo& ci) override {
    MeshT& mesh = Base::mesh();
    for (const int e : pending_) {
      const int j = e % P_;
      double best = HUGE_VAL;
      typename MeshT::FaceHandle home;
      for (auto fh : mesh.vf_range(ci.v1)) {
        Eigen::Vector3d t[3];
        int k = 0;
        for (auto v : mesh.fv_range(fh)) t[k++] = this->solver().posed(v, j);
        Eigen::Vector3d bary;
        const double d = closest_barycentric(t, points_[size_t(e)], bary);
        if (d < best) best = d, home = fh;
      }
      // v1 without a face would leave the point nowhere: the bound is then no longer one.
      if (!home.is_valid()) {
        bound2_ = HUGE_VAL;
        continue;
      }
      held_[home.idx()].push_back(e);
      bound2_ = std::max(bound2_, best);
    }
    pending_.clear();
  }

protected:
  void contribute(SolverSettings& s) const override { s.recheck_stale = s.recheck_stale || std::isfinite(max_); }
  bool now_refuses(const CollapseInfo& ci) override { return !legal(ci); }

  float price(const CollapseInfo& ci) override {
    if (this->solver().cannot_win(ci)) return float(Base::LEGAL_COLLAPSE);
    return legal(ci) ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

private:
  using Solver = SolverModuleT<MeshT>;

  // Whether every point held by a face the collapse changes finds a surviving face within the limit.
  bool legal(const CollapseInfo& ci) {
    if (!std::isfinite(max_)) return true;
    Eigen::Vector3d rest;
    Influences w;
    this->solver().placement_of(ci, rest, w);
    surviving_faces(Base::mesh(), ci.v0, ci.v1, ring_);
    merged_.resize(size_t(P_));
    for (int j = 0; j < P_; ++j) merged_[j] = this->solver().posed_point(rest, w, j);
    const double limit2 = max_ * max_;
    bool legal = true;
    for_changed_faces(ci, [&](typename MeshT::FaceHandle fh) {
      for (const int e : held_[fh.idx()]) {
        if (!legal) return;
        const int j = e % P_;
        bool near = false;
        for (const RingFace& f : ring_) {
          const Eigen::Vector3d t[3] = {merged_[j], posed(f[1], j), posed(f[2], j)};
          Eigen::Vector3d bary;
          if (closest_barycentric(t, points_[size_t(e)], bary) <= limit2) {
            near = true;
            break;
          }
        }
        legal = near;
      }
    });
    return legal;
  }

  Eigen::Vector3d posed(int v, int j) { return this->solver().posed(typename MeshT::VertexHandle(v), j); }

  // Calls f once for each face around v0 or v1.
  template <typename F>
  void for_changed_faces(const CollapseInfo& ci, F f) {
    MeshT& mesh = Base::mesh();
    for (auto fh : mesh.vf_range(ci.v0)) f(fh);
    for (auto fh : mesh.vf_range(ci.v1)) {
      bool has_v0 = false;
      for (auto v : mesh.fv_range(fh)) has_v0 = has_v0 || v == ci.v0;
      if (!has_v0) f(fh);
    }
  }

  double max_ = HUGE_VAL;
  int P_ = 1;
  std::vector<Eigen::Vector3d> points_;  // original vertex v in pose j at v * P_ + j
  std::vector<std::vector<int>> held_;   // per face: the points (v * P_ + j) it holds
  std::vector<int> pending_;
  std::vector<RingFace> ring_;
  std::vector<Eigen::Vector3d> merged_;
  double bound2_ = 0.0;
};

}  // namespace OpenMeshSkinned
