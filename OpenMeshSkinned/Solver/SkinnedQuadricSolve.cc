#include "OpenMeshSkinned/Solver/SkinnedQuadricSolve.hh"

#include "OpenMeshSkinned/Solver/JointQuadrics.hh"
#include "OpenMeshSkinned/Solver/TruncatedSolve.hh"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace OpenMeshSkinned {

namespace {

// How far (in edge lengths) from the edge's midpoint a solved position may lie.
constexpr double kMaxReach = 1.0;

// C(a) with the rest-pose attribute quadric added: what a position costs at weights a.
Eigen::Matrix4d blended(const EdgeProblem& p, const JointQuadrics& g, const WeightSolver::Vector& a) {
  Eigen::Matrix4d c = g.blend(a);
  c += p.attribute.matrix();
  return c;
}

int count_nonzero(const WeightSolver::Vector& a) { return static_cast<int>((a.array() > 0.0).count()); }

// The vertex step, then the best of it, the endpoints and the midpoint: the truncated solve is the
// optimum only along the constrained directions, and a fully singular system has no solve at all.
Eigen::Vector3d place(const EdgeProblem& p, const JointQuadrics& g, const WeightSolver::Vector& a) {
  const Eigen::Vector3d mid = 0.5 * (p.pa + p.pb);
  Eigen::Vector3d cand[4] = {mid, p.pa, p.pb, mid};
  bool full_rank = false;
  const Eigen::Matrix4d c = blended(p, g, a);
  int n = skinned_vertex_step(c, mid, cand[3], full_rank) ? 4 : 3;
  // A thin part (a tail, a finger) has quadrics whose minimum lies far along its axis: the error keeps
  // falling a little as the vertex slides out of the mesh. Optima more than an edge length beyond the
  // edge's midpoint are such valleys, not features: keep to the endpoints and the midpoint there.
  if (n == 4 && (cand[3] - mid).squaredNorm() > kMaxReach * kMaxReach * (p.pa - p.pb).squaredNorm()) n = 3;
  if (n == 4 && full_rank) return cand[3];  // the exact minimiser: nothing can beat it
  int best = 0;
  double be = JointQuadrics::energy(c, cand[0]);
  for (int i = 1; i < n; ++i) {
    const double ei = JointQuadrics::energy(c, cand[i]);
    if (ei < be) {
      be = ei;
      best = i;
    }
  }
  return cand[best];
}

// Alternating minimisation (paper 3.1/3.2); each half-step cannot increase E, so stop when it stalls.
double alternate(const EdgeProblem& p, const JointQuadrics& g, const SolveSettings& s, WeightSolver& weights, int cap,
                 WeightSolver::Vector& a, Eigen::Vector3d& v) {
  WeightSolver::Matrix H;
  double e_prev = std::numeric_limits<double>::infinity();
  double e = e_prev;
  for (int it = 0; it < std::max(1, s.max_iterations); ++it) {
    v = place(p, g, a);
    if (p.support == 1) return JointQuadrics::energy(blended(p, g, a), v);
    g.weight_matrix(v, H);
    e = cap < p.support ? weights.solve_capped(H, p.start, cap, s.strategy, a) : weights.solve(H, p.start, a);
    if (!(e < e_prev * (1.0 - s.tolerance))) break;
    e_prev = e;
  }
  return JointQuadrics::energy(blended(p, g, a), v);
}

// As alternate(), with the weights restricted to their current support.
double alternate_fixed_support(const EdgeProblem& p, const JointQuadrics& g, const SolveSettings& s,
                               WeightSolver& weights, WeightSolver::Vector& a, Eigen::Vector3d& v) {
  Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, WeightSolver::kMaxJoints, 1> active(p.support);
  for (int k = 0; k < p.support; ++k) active[k] = a[k] > 0.0;
  WeightSolver::Matrix H;
  double e_prev = std::numeric_limits<double>::infinity();
  for (int it = 0; it < std::max(1, s.max_iterations); ++it) {
    v = place(p, g, a);
    g.weight_matrix(v, H);
    const double e = weights.solve(H, p.start, a, &active);
    if (!(e < e_prev * (1.0 - s.tolerance))) break;
    e_prev = e;
  }
  return JointQuadrics::energy(blended(p, g, a), v);
}

[[maybe_unused]] bool transforms_finite(const EdgeProblem& p) {
  for (int j = 0; j < p.poses; ++j)
    for (int k = 0; k < p.support; ++k)
      if (!p.M(j, k).allFinite()) return false;
  return true;
}

Influences to_influences(const EdgeProblem& p, const WeightSolver::Vector& a) {
  Influences out;
  for (int k = 0; k < p.support; ++k)
    if (a[k] > 0.0) out.push(p.joint[k], a[k]);
  out.normalize();
  out.sort();
  return out;
}

}  // namespace

double skinned_energy(const EdgeProblem& p, const Eigen::Vector3d& v, const WeightSolver::Vector& a) {
  double e = 0.0;
  for (int j = 0; j < p.poses; ++j) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < p.support; ++k) x += a[k] * (p.M(j, k) * v.homogeneous());
    e += p.quadric[j](x);
  }
  return std::max(e + p.attribute(v), 0.0);
}

bool skinned_vertex_step(const Eigen::Matrix4d& c, const Eigen::Vector3d& ref, Eigen::Vector3d& v, bool& full_rank) {
  full_rank = false;
  if (!truncated_solve(c.topLeftCorner<3, 3>(), -c.topRightCorner<3, 1>(), ref, v, &full_rank)) return false;
  return v.allFinite();
}

void solve_collapse(const EdgeProblem& p, const SolveSettings& s, WeightSolver& weights, CollapseResult& out) {
  // PoseCacheT refuses non-finite poses: one here is a bug upstream. Finite poses can still overflow the
  // quadrics of huge coordinates; the weight solve refuses those (an infinite error: no collapse).
  assert(transforms_finite(p));
  thread_local JointQuadrics g;  // 8 KB: not on every call's stack, not shared between threads
  g.build(p);
  WeightSolver::Vector a = p.start;
  Eigen::Vector3d v;
  double e = alternate(p, g, s, weights, p.support > 1 ? Influences::kCapacity : 1, a, v);
  if (count_nonzero(a) > s.max_influences) {
    // Cap after the free optimum (paper 3.2), then optimise again on the kept joints only.
    WeightSolver::Matrix H;
    g.weight_matrix(v, H);
    weights.solve_capped(H, p.start, s.max_influences, s.strategy, a);
    e = alternate_fixed_support(p, g, s, weights, a, v);
  }
  out.valid = v.allFinite() && std::isfinite(e);
  out.position = v;
  out.error = e;
  out.area = 0.0;
  for (const PoseQuadric& q : p.quadric) out.area += q.A().trace() / std::max(1, p.poses);
  out.weights = to_influences(p, a);
}

Influences reduce_influences(const EdgeProblem& p, const SolveSettings& s, WeightSolver& weights) {
  assert(transforms_finite(p));
  WeightSolver::Vector a(p.support);
  WeightSolver::Matrix H;
  thread_local JointQuadrics g;
  g.build(p);
  g.weight_matrix(p.pa, H);
  weights.solve_capped(H, p.start, s.max_influences, s.strategy, a);
  return to_influences(p, a);
}

}  // namespace OpenMeshSkinned
