#include "graspkit/math/nonnegative_least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace graspkit {

namespace {

// The unconstrained least-squares solution on the passive columns (the others held at 0). The
// complete orthogonal decomposition gives the minimum-norm one when those columns are dependent,
// as friction-cone edges often are.
Eigen::VectorXd passiveSolution(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                const std::vector<int>& passive) {
  Eigen::MatrixXd columns(A.rows(), static_cast<Eigen::Index>(passive.size()));
  for (std::size_t i = 0; i < passive.size(); ++i) columns.col(i) = A.col(passive[i]);
  const Eigen::VectorXd solved = columns.completeOrthogonalDecomposition().solve(b);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(A.cols());
  for (std::size_t i = 0; i < passive.size(); ++i) z[passive[i]] = solved[i];
  return z;
}

}  // namespace

NonnegativeLeastSquaresResult nonnegativeLeastSquares(
    const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
    const NonnegativeLeastSquaresRequest& request) {
  const Eigen::Index n = A.cols();
  NonnegativeLeastSquaresResult result;
  result.x = Eigen::VectorXd::Zero(n);
  std::vector<bool> is_passive(n, false);
  // A column that rounding turned away at once (its solution not positive when it entered) is
  // not offered again until x changes, so the method cannot cycle on it.
  std::vector<bool> turned_away(n, false);
  // Gradients below this are rounding: the scale of A^T b.
  const double tolerance =
      10.0 * std::numeric_limits<double>::epsilon() * std::max<Eigen::Index>(A.rows(), n) *
      std::max(1.0, A.cwiseAbs().maxCoeff()) * std::max(1.0, b.cwiseAbs().maxCoeff());
  const int max_iterations = std::max<int>(1, request.iterationsPerColumn * static_cast<int>(n));
  Eigen::VectorXd r = b;
  for (; result.iterations < max_iterations; ++result.iterations) {
    result.residual = r.norm();
    if (result.residual <= request.enoughResidual) {
      result.converged = true;
      return result;
    }
    // The column whose growth lowers the residual fastest, among those held at 0.
    const Eigen::VectorXd w = A.transpose() * r;
    Eigen::Index entering = -1;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!is_passive[j] && !turned_away[j] && w[j] > tolerance &&
          (entering < 0 || w[j] > w[entering]))
        entering = j;
    if (entering < 0) {
      result.converged = true;  // Kuhn-Tucker conditions hold: x is the minimizer
      return result;
    }
    is_passive[entering] = true;
    // Inner loop: move towards the passive set's least-squares solution, as far as x stays >= 0,
    // dropping the columns that reach 0, until that solution is itself nonnegative.
    for (;;) {
      std::vector<int> passive;
      for (Eigen::Index j = 0; j < n; ++j)
        if (is_passive[j]) passive.push_back(static_cast<int>(j));
      const Eigen::VectorXd z = passiveSolution(A, b, passive);
      double step = 1.0;
      for (int j : passive)
        if (z[j] <= 0.0) step = std::min(step, result.x[j] / (result.x[j] - z[j]));
      if (step <= 0.0 && z[entering] <= 0.0 && result.x[entering] == 0.0) {
        is_passive[entering] = false;
        turned_away[entering] = true;
        break;
      }
      result.x += step * (z - result.x);
      std::fill(turned_away.begin(), turned_away.end(), false);
      if (step >= 1.0) break;
      bool dropped = false;
      for (int j : passive) {
        if (result.x[j] <= tolerance * 1e-3 || (z[j] <= 0.0 && result.x[j] <= 0.0)) {
          result.x[j] = 0.0;
          is_passive[j] = false;
          dropped = true;
        }
      }
      if (!dropped) break;  // rounding left every column positive: take the step as it is
    }
    result.x = result.x.cwiseMax(0.0);
    r = b - A * result.x;
  }
  result.residual = r.norm();
  result.converged = result.residual <= request.enoughResidual;
  return result;
}

}  // namespace graspkit
