#pragma once
/** \file WeightSolver.hh
 *  The constrained skin-weight problem of Landreneau & Schaefer 3.2:
 *
 *      minimise  a^T H a + mu |a - a0|^2   subject to  a >= 0,  sum(a) = 1,  at most n non-zero,
 *
 *  where H = sum_poses V^T Q V is the weight Gram matrix at a fixed vertex position and a0 is the start
 *  (the endpoints' average). mu is tiny: it plays the paper's min-norm offset, choosing among the many
 *  minimisers when poses are fewer than joints.
 *
 *  Without the bound a >= 0 the problem has a closed form (the paper's KKT system, eq. 4). A primal
 *  active-set loop around it (drop the most negative joint, add back a joint whose KKT condition fails)
 *  usually ends on a point that passes the KKT conditions of the bounded problem, which is then the
 *  optimum: the problem is strictly convex. When it does not (cycling, singular systems), Ceres solves
 *  the problem on the unit sphere: a_k = s_k^2
 *  with |s| = 1 gives both a >= 0 and sum(a) = 1 exactly, with no penalty terms and no equality
 *  constraint (which Ceres does not have), and the sphere is a manifold Ceres supports natively.
 */

#include <Eigen/Core>

#include <cstddef>
#include <memory>

namespace OpenMeshSkinned {

/// How the cap on influences is enforced when the unconstrained optimum uses more joints.
enum class CapStrategy {
  TopN,    ///< the paper: keep the n heaviest, re-solve on them
  Greedy,  ///< drop the joint whose removal raises the error least, re-solve, repeat until n remain
};

struct WeightSolverStats {
  size_t solves = 0;        ///< constrained problems solved
  size_t kkt_feasible = 0;  ///< answered by the closed form (on a support it found), proven optimal
  size_t ceres_calls = 0;
  size_t non_finite = 0;  ///< problems refused: a non-finite Gram matrix or start (the error is then infinite)

  WeightSolverStats& operator+=(const WeightSolverStats& o) {
    solves += o.solves;
    kkt_feasible += o.kkt_feasible;
    ceres_calls += o.ceres_calls;
    non_finite += o.non_finite;
    return *this;
  }
};

class WeightSolver {
public:
  static constexpr int kMaxJoints = 16;
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxJoints, kMaxJoints>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxJoints, 1>;

  WeightSolver();
  ~WeightSolver();
  WeightSolver(const WeightSolver&) = delete;
  WeightSolver& operator=(const WeightSolver&) = delete;

  /** Minimises over the joints marked in \p active (all when empty) with a >= 0 and sum(a) = 1.
   *  Returns the objective a^T H a (without the pull term). Inactive joints get weight 0. A non-finite
   *  \p H or \p start has no answer: the error is infinite and \p alpha the start's weights. */
  double solve(const Matrix& H, const Vector& start, Vector& alpha,
               const Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, kMaxJoints, 1>* active = nullptr);

  /** As solve(), with at most \p cap non-zero weights, enforced by \p strategy. */
  double solve_capped(const Matrix& H, const Vector& start, int cap, CapStrategy strategy, Vector& alpha);

  const WeightSolverStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }

  /// Always run Ceres, skipping the closed form (to cross-check the two, and to benchmark Ceres).
  void set_force_ceres(bool on) { force_ceres_ = on; }
  bool force_ceres() const { return force_ceres_; }

  /// Relative size of mu against the mean diagonal of H.
  void set_regularization(double r) { reg_ = r; }
  double regularization() const { return reg_; }

private:
  using Mask = Eigen::Matrix<bool, Eigen::Dynamic, 1, 0, kMaxJoints, 1>;
  bool solve_kkt(const Matrix& H, const Vector& start, double mu, const Mask& active, Vector& alpha,
                 bool allow_negative) const;
  int violated(const Matrix& H, const Vector& start, double mu, const Mask& active, const Vector& alpha) const;
  bool active_set(const Matrix& H, const Vector& start, double mu, const Mask& active, Mask support,
                  Vector& alpha) const;
  void solve_ceres(const Matrix& H, const Vector& start, double mu, const Mask& active, Vector& alpha);

  struct CeresCache;
  std::unique_ptr<CeresCache> ceres_;
  WeightSolverStats stats_;
  double reg_ = 1e-7;
  bool force_ceres_ = false;
};

}  // namespace OpenMeshSkinned
