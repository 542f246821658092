#include "OpenMeshSkinned/Solver/WeightSolver.hh"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace OpenMeshSkinned {
namespace {

constexpr int kMax = WeightSolver::kMaxJoints;
using Mat = WeightSolver::Matrix;
using Vec = WeightSolver::Vector;
using Mask = Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, kMax, 1>;

// The refused solve's weights: the start's heaviest \p cap, summing to one (all zero when the start is
// unusable too), so that a caller that keeps the weights whatever the error still holds a valid skin.
void truncated_start(const Vec& start, int cap, const Mask* active, Vec& alpha) {
  const int m = static_cast<int>(start.size());
  alpha.setZero(m);
  std::array<int, kMax> order;
  int n = 0;
  for (int k = 0; k < m; ++k)
    if ((!active || (*active)[k]) && std::isfinite(start[k]) && start[k] > 0.0) order[n++] = k;
  std::sort(order.begin(), order.begin() + n, [&](int a, int b) { return start[a] > start[b]; });
  double sum = 0.0;
  for (int i = 0; i < std::min(n, cap); ++i) sum += alpha[order[i]] = start[order[i]];
  if (sum > 0.0) alpha /= sum;
}

}  // namespace

bool WeightSolver::solve_kkt(const Mat& H, const Vec& start, double mu, const Mask& active, Vec& alpha,
                             bool allow_negative) const {
  const int m = static_cast<int>(H.rows());
  std::array<int, kMax> idx;
  int r = 0;
  for (int k = 0; k < m; ++k)
    if (active[k]) idx[r++] = k;
  // Minimise a^T (H + mu I) a - 2 mu a0^T a subject to sum(a) = 1 (the paper's KKT system, eq. 4) by the
  // null-space method: with the last active weight 1 - sum(others), the r - 1 free weights solve the
  // reduced system N^T P N w = N^T (b - P e_r), symmetric positive definite (P = H + mu I is), so an LDLT
  // of size r - 1 instead of a pivoted LU of the (r + 1)-square saddle-point matrix; the same answer.
  // Scaled so that P is of order 1 (Gram matrices of 1e9 and more otherwise lose the small pull term).
  double diag = mu;
  for (int i = 0; i < r; ++i) diag += std::abs(H(idx[i], idx[i])) / r;
  const double s = 1.0 / diag;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> x(r);
  if (r == 1) {
    x[0] = 1.0;
  } else {
    const int n = r - 1, last = idx[r - 1];
    const double p_rr = s * (H(last, last) + mu), b_r = s * mu * start[last];
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax> R(n, n);
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> g(n);
    for (int i = 0; i < n; ++i) {
      const double p_ir = s * H(idx[i], last);
      for (int j = 0; j < n; ++j) R(i, j) = s * H(idx[i], idx[j]) - p_ir - s * H(last, idx[j]) + p_rr;
      R(i, i) += s * mu;
      g[i] = (s * mu * start[idx[i]] - p_ir) - (b_r - p_rr);
    }
    const Eigen::LDLT<decltype(R)> ldlt(R);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> w = ldlt.solve(g);
    double rest = 1.0;
    for (int i = 0; i < n; ++i) {
      x[i] = w[i];
      rest -= w[i];
    }
    x[n] = rest;
  }
  alpha.setZero(m);
  for (int i = 0; i < r; ++i)
    if (!std::isfinite(x[i])) return false;
  if (allow_negative) {
    for (int i = 0; i < r; ++i) alpha[idx[i]] = x[i] < -1e-12 ? x[i] : std::max(0.0, x[i]);
    return true;
  }
  double sum = 0.0;
  for (int i = 0; i < r; ++i) {
    if (x[i] < -1e-12) return false;
    alpha[idx[i]] = std::max(0.0, x[i]);
    sum += alpha[idx[i]];
  }
  if (!(sum > 0.0)) return false;
  alpha /= sum;
  return true;
}

int WeightSolver::violated(const Mat& H, const Vec& start, double mu, const Mask& active, const Vec& alpha) const {
  // The problem is strictly convex (H is PSD and mu > 0), so a point meeting the KKT conditions is THE
  // optimum. With g the gradient, the multiplier of sum(a) = 1 is g_k on the support, and every joint
  // off the support must have g_k >= that multiplier (moving weight onto it cannot help). Returns the
  // joint that breaks this most, or -1 when none does.
  const int m = static_cast<int>(H.rows());
  const Vec g = 2.0 * (H * alpha) + 2.0 * mu * (alpha - start);
  double lambda = 0.0;
  int n = 0;
  for (int k = 0; k < m; ++k)
    if (active[k] && alpha[k] > 0.0) {
      lambda += g[k];
      ++n;
    }
  if (n == 0) return -1;
  lambda /= n;
  // Relative to the gradient, at the accuracy a nearly singular KKT solve delivers.
  const double tol = 1e-7 * (std::abs(lambda) + g.cwiseAbs().maxCoeff() + 1e-300);
  int worst = -1;
  for (int k = 0; k < m; ++k)
    if (active[k] && alpha[k] == 0.0 && g[k] < lambda - tol && (worst < 0 || g[k] < g[worst])) worst = k;
  return worst;
}

bool WeightSolver::active_set(const Mat& H, const Vec& start, double mu, const Mask& active, Mask support,
                              Vec& alpha) const {
  // Primal active set on the paper's closed form: drop the most negative joint from the support, or add
  // back the joint whose KKT condition fails most, until violated() finds none: the point is then optimal.
  const int m = static_cast<int>(H.rows());
  Vec x;
  for (int round = 0; round < 4 * m + 4; ++round) {
    if (support.count() == 0 || !solve_kkt(H, start, mu, support, x, /*allow_negative=*/true)) return false;
    int worst = -1;
    for (int k = 0; k < m; ++k)
      if (support[k] && x[k] < 0.0 && (worst < 0 || x[k] < x[worst])) worst = k;
    if (worst >= 0) {
      support[worst] = false;
      continue;
    }
    // A nearly singular system (weight Gram matrices of 1e9 and more, from large coordinates) can return
    // a point off sum(a) = 1: not an answer (Ceres takes over).
    const double sum = x.sum();
    if (!(std::abs(sum - 1.0) <= 1e-6)) return false;
    alpha = x / sum;
    const int add = violated(H, start, mu, active, alpha);
    if (add < 0) return true;
    support[add] = true;
  }
  return false;
}

double WeightSolver::solve(const Mat& H, const Vec& start, Vec& alpha, const Mask* active_in) {
  const int m = static_cast<int>(H.rows());
  ++stats_.solves;
  if (!H.allFinite() || !start.allFinite()) {
    // Huge coordinates can overflow the Gram matrix: no answer, and an iterative solve would not end.
    ++stats_.non_finite;
    truncated_start(start, m, active_in, alpha);
    return std::numeric_limits<double>::infinity();
  }
  const Mask active = active_in ? *active_in : Mask::Constant(m, true);
  const double mu = std::max(reg_ * H.diagonal().cwiseAbs().sum() / std::max(m, 1), 1e-300);

  if (!force_ceres_ && active.count() == 2) {
    // Two joints: a = (t, 1 - t) on the segment, a quadratic in t; its clamped stationary point is exact.
    int i = 0;
    while (!active[i]) ++i;
    int j = i + 1;
    while (!active[j]) ++j;
    // f(t) = [t, 1-t] (H + mu I) [t, 1-t]^T - 2 mu (a0_i t + a0_j (1-t)) + const
    const double hii = H(i, i) + mu, hjj = H(j, j) + mu, hij = H(i, j);
    const double curv = hii + hjj - 2.0 * hij;                    // f'' / 2
    const double slope = hij - hjj - mu * (start[i] - start[j]);  // f'(0) / 2
    double t = curv > 0.0 ? -slope / curv : (slope < 0.0 ? 1.0 : 0.0);
    t = std::clamp(t, 0.0, 1.0);
    alpha.setZero(m);
    alpha[i] = t;
    alpha[j] = 1.0 - t;
    ++stats_.kkt_feasible;
    return alpha.dot(H * alpha);
  }
  if (!force_ceres_ && active_set(H, start, mu, active, active, alpha)) {
    ++stats_.kkt_feasible;
    return alpha.dot(H * alpha);
  }

  solve_ceres(H, start, mu, active, alpha);
  // The sphere parametrisation reaches zero weights only asymptotically (and slowly): take the joints
  // Ceres kept as the starting support and finish exactly with the closed form.
  const double e_ceres = alpha.dot(H * alpha) + mu * (alpha - start).squaredNorm();
  Mask kept = active;
  for (int k = 0; k < m; ++k) kept[k] = active[k] && alpha[k] > 1e-4;
  Vec polished;
  if (active_set(H, start, mu, active, kept, polished)) {
    const double e_pol = polished.dot(H * polished) + mu * (polished - start).squaredNorm();
    if (e_pol <= e_ceres * (1.0 + 1e-9) + 1e-300) alpha = polished;
  }
  for (int k = 0; k < m; ++k)
    if (alpha[k] < 1e-9) alpha[k] = 0.0;
  alpha /= alpha.sum();
  return alpha.dot(H * alpha);
}

double WeightSolver::solve_capped(const Mat& H, const Vec& start, int cap, CapStrategy strategy, Vec& alpha) {
  const int m = static_cast<int>(H.rows());
  double e = solve(H, start, alpha);
  int nnz = static_cast<int>((alpha.array() > 0.0).count());
  if (!std::isfinite(e)) {
    truncated_start(start, cap, nullptr, alpha);
    return e;
  }
  if (nnz <= cap) return e;

  Mask active(m);
  for (int k = 0; k < m; ++k) active[k] = alpha[k] > 0.0;
  if (strategy == CapStrategy::TopN) {
    std::array<int, kMax> order;
    for (int k = 0; k < m; ++k) order[k] = k;
    std::sort(order.begin(), order.begin() + m, [&](int a, int b) { return alpha[a] > alpha[b]; });
    active.setConstant(false);
    for (int i = 0; i < cap; ++i) active[order[i]] = true;
    return solve(H, start, alpha, &active);
  }
  // Greedy: try removing each remaining joint; keep the removal that hurts least.
  Vec trial, best_alpha = alpha;
  while (nnz > cap) {
    double best = std::numeric_limits<double>::infinity();
    int best_k = -1;
    for (int k = 0; k < m; ++k) {
      if (!active[k]) continue;
      active[k] = false;
      const double ek = solve(H, start, trial, &active);
      active[k] = true;
      if (ek < best) {
        best = ek;
        best_k = k;
        best_alpha = trial;
      }
    }
    if (best_k < 0) {  // no removal has a finite error
      ++stats_.non_finite;
      truncated_start(start, cap, nullptr, alpha);
      return std::numeric_limits<double>::infinity();
    }
    active[best_k] = false;
    alpha = best_alpha;
    e = best;
    // The re-solve may itself have zeroed more joints.
    for (int k = 0; k < m; ++k) active[k] = active[k] && alpha[k] > 0.0;
    nnz = static_cast<int>(active.count());
  }
  return e;
}

}  // namespace OpenMeshSkinned
