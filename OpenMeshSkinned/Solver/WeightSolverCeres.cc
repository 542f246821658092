// The weight solve's fallback, for when the closed-form active set (WeightSolver.cc) finds no answer: the
// problem on the sphere (a = s .* s, |s| = 1) solved with Ceres. Apart from the closed form so that only
// this file depends on Ceres.
#include "OpenMeshSkinned/Solver/WeightSolver.hh"

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <cmath>

namespace OpenMeshSkinned {
namespace {

constexpr int kMax = WeightSolver::kMaxJoints;
using Mat = WeightSolver::Matrix;
using Vec = WeightSolver::Vector;

// Residual r(s) = U (s .* s) - z with U^T U = H + mu I and U^T z = mu a0, so that
// |r|^2 = a^T (H + mu I) a - 2 mu a0^T a + const: the weight objective, as a least-squares problem in s.
// Jacobian dr/ds = U diag(2 s).
class SphereWeightCost final : public ceres::CostFunction {
public:
  explicit SphereWeightCost(int n) : n_(n) {
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(n);
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMax, kMax> U;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1> z;

  // Returns false on a non-finite result: Ceres then rejects the step quietly, where a true with NaN in it
  // makes it log a page per evaluation.
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* s = parameters[0];
    bool finite = true;
    for (int i = 0; i < n_; ++i) {
      double r = -z[i];
      for (int k = 0; k < n_; ++k) r += U(i, k) * s[k] * s[k];
      residuals[i] = r;
      finite &= std::isfinite(r);
    }
    if (jacobians && jacobians[0])
      for (int i = 0; i < n_; ++i)
        for (int k = 0; k < n_; ++k) finite &= std::isfinite(jacobians[0][i * n_ + k] = U(i, k) * 2.0 * s[k]);
    return finite;
  }

private:
  int n_;
};

}  // namespace

// One problem per size, built once and reused: only the cost's data and the start change between solves.
struct WeightSolver::CeresCache {
  struct Slot {
    std::unique_ptr<ceres::Problem> problem;
    SphereWeightCost* cost = nullptr;  // owned by problem
    std::array<double, kMax> s{};
  };
  std::array<Slot, kMax + 1> slots;
  ceres::Solver::Options options;

  CeresCache() {
    options.linear_solver_type = ceres::DENSE_QR;
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    options.max_num_iterations = 100;
    options.function_tolerance = 1e-14;
    options.gradient_tolerance = 1e-16;
    options.parameter_tolerance = 1e-12;
    options.num_threads = 1;
  }

  Slot& slot(int n) {
    Slot& sl = slots[n];
    if (!sl.problem) {
      ceres::Problem::Options po;
      sl.problem = std::make_unique<ceres::Problem>(po);
      sl.cost = new SphereWeightCost(n);
      sl.problem->AddResidualBlock(sl.cost, nullptr, sl.s.data());
      sl.problem->SetManifold(sl.s.data(), new ceres::SphereManifold<ceres::DYNAMIC>(n));
    }
    return sl;
  }
};

WeightSolver::WeightSolver() : ceres_(std::make_unique<CeresCache>()) {}
WeightSolver::~WeightSolver() = default;

void WeightSolver::solve_ceres(const Mat& H, const Vec& start, double mu, const Mask& active, Vec& alpha) {
  const int m = static_cast<int>(H.rows());
  std::array<int, kMax> idx;
  int r = 0;
  for (int k = 0; k < m; ++k)
    if (active[k]) idx[r++] = k;
  alpha.setZero(m);
  if (r == 1) {
    alpha[idx[0]] = 1.0;
    return;
  }
  Mat Hr(r, r);
  Vec a0(r);
  for (int i = 0; i < r; ++i) {
    for (int j = 0; j < r; ++j) Hr(i, j) = H(idx[i], idx[j]);
    Hr(i, i) += mu;
    a0[i] = start[idx[i]];
  }
  CeresCache::Slot& sl = ceres_->slot(r);
  const Eigen::LLT<Mat> llt(Hr);
  sl.cost->U = llt.matrixU();
  sl.cost->z = llt.matrixU().transpose().solve(Vec(mu * a0));
  // Start inside the simplex: where a start weight is 0, its square root would sit on a stationary point
  // of the parametrisation (d a / d s = 0) and never move, so every joint starts with a little weight.
  double norm = 0.0;
  for (int i = 0; i < r; ++i) {
    sl.s[i] = std::sqrt(std::max(a0[i], 0.0) + 1e-3);
    norm += sl.s[i] * sl.s[i];
  }
  norm = std::sqrt(norm);
  for (int i = 0; i < r; ++i) sl.s[i] /= norm;
  ceres::Solver::Summary summary;
  ceres::Solve(ceres_->options, sl.problem.get(), &summary);
  ++stats_.ceres_calls;
  double sum = 0.0;
  for (int i = 0; i < r; ++i) sum += sl.s[i] * sl.s[i];
  for (int i = 0; i < r; ++i) alpha[idx[i]] = sl.s[i] * sl.s[i] / sum;
}

}  // namespace OpenMeshSkinned
