// Nonnegative least squares (math/nonnegative_least_squares.hpp) against closed forms and a
// second method: the minimizer's support S makes x_S the unconstrained least-squares solution on
// S's columns, so the smallest residual over every subset whose solution is nonnegative is the
// minimum. Small problems try all 2^n subsets.

#include "graspkit/math/nonnegative_least_squares.hpp"

#include <gtest/gtest.h>

#include <random>

namespace graspkit {
namespace {

Eigen::MatrixXd randomMatrix(int rows, int columns, std::mt19937& random) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A(rows, columns);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) A(i, j) = normal(random);
  return A;
}

// The smallest residual over the subsets of A's columns whose least-squares solution is >= 0.
double bruteForceResidual(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  double best = b.norm();  // the empty subset: x = 0
  const int n = static_cast<int>(A.cols());
  for (int mask = 1; mask < (1 << n); ++mask) {
    std::vector<int> subset;
    for (int j = 0; j < n; ++j)
      if (mask & (1 << j)) subset.push_back(j);
    Eigen::MatrixXd columns(A.rows(), static_cast<Eigen::Index>(subset.size()));
    for (std::size_t i = 0; i < subset.size(); ++i) columns.col(i) = A.col(subset[i]);
    const Eigen::VectorXd x = columns.completeOrthogonalDecomposition().solve(b);
    if (x.minCoeff() < -1e-12) continue;
    best = std::min(best, (columns * x - b).norm());
  }
  return best;
}

TEST(NonnegativeLeastSquares, TheIdentityClipsNegativeEntriesToZero) {
  const Eigen::VectorXd b = (Eigen::VectorXd(5) << 1.5, -2.0, 0.0, 3.25, -0.5).finished();
  const auto result = nonnegativeLeastSquares(Eigen::MatrixXd::Identity(5, 5), b);
  ASSERT_TRUE(result.converged);
  const Eigen::VectorXd expected = b.cwiseMax(0.0);
  EXPECT_LT((result.x - expected).norm(), 1e-12);
  EXPECT_NEAR(result.residual, std::sqrt(2.0 * 2.0 + 0.5 * 0.5), 1e-12);
}

TEST(NonnegativeLeastSquares, APointInsideTheConeOfTheColumnsIsReachedExactly) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> share(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::MatrixXd A = randomMatrix(6, 24, random);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(24);
    for (int j = 0; j < 24; j += 3) x[j] = share(random);
    const Eigen::VectorXd b = A * x;
    const auto result = nonnegativeLeastSquares(A, b);
    ASSERT_TRUE(result.converged) << trial;
    EXPECT_GE(result.x.minCoeff(), 0.0);
    EXPECT_LT(result.residual, 1e-10 * std::max(1.0, b.norm())) << trial;
    EXPECT_NEAR(result.residual, (A * result.x - b).norm(), 1e-12);
  }
}

TEST(NonnegativeLeastSquares, TheMinimumAgreesWithEverySubsetTried) {
  std::mt19937 random(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 2 + trial % 4, columns = 3 + trial % 7;
    const Eigen::MatrixXd A = randomMatrix(rows, columns, random);
    const Eigen::VectorXd b = randomMatrix(rows, 1, random);
    const auto result = nonnegativeLeastSquares(A, b);
    ASSERT_TRUE(result.converged) << trial;
    EXPECT_GE(result.x.minCoeff(), 0.0);
    EXPECT_NEAR(result.residual, bruteForceResidual(A, b), 1e-9) << trial;
    // Kuhn-Tucker: no column held at 0 would lower the residual, and the others are at a
    // stationary point.
    const Eigen::VectorXd w = A.transpose() * (b - A * result.x);
    for (int j = 0; j < columns; ++j) {
      EXPECT_LE(w[j], 1e-9) << trial;
      if (result.x[j] > 1e-9) EXPECT_NEAR(w[j], 0.0, 1e-9) << trial;
    }
  }
}

TEST(NonnegativeLeastSquares, DependentColumnsAsFrictionPyramidsHaveThem) {
  // Two contacts' pyramids in the plane, each a normal +- mu times the tangent: b along the
  // normals is carried, b along the tangent beyond mu times the normal load is not.
  const double mu = 0.5;
  Eigen::MatrixXd A(2, 4);
  A << mu, -mu, mu, -mu,  //
      1.0, 1.0, 1.0, 1.0;
  const auto inside = nonnegativeLeastSquares(A, Eigen::Vector2d(0.9 * mu, 1.0));
  EXPECT_LT(inside.residual, 1e-12);
  const auto outside = nonnegativeLeastSquares(A, Eigen::Vector2d(2.0 * mu, 1.0));
  // The nearest carried load is on the cone's edge: (mu, 1) * (2 mu * mu + 1) / (mu^2 + 1).
  const Eigen::Vector2d edge(mu, 1.0);
  const Eigen::Vector2d nearest =
      edge * edge.dot(Eigen::Vector2d(2.0 * mu, 1.0)) / edge.squaredNorm();
  EXPECT_NEAR(outside.residual, (nearest - Eigen::Vector2d(2.0 * mu, 1.0)).norm(), 1e-12);
}

TEST(NonnegativeLeastSquares, StopsOnceTheResidualIsSmallEnough) {
  std::mt19937 random(3);
  const Eigen::MatrixXd A = randomMatrix(6, 48, random).cwiseAbs();
  const Eigen::VectorXd b = A * Eigen::VectorXd::Ones(48);
  const auto result = nonnegativeLeastSquares(A, b, {.enoughResidual = 1e-3 * b.norm()});
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.residual, 1e-3 * b.norm());
}

}  // namespace
}  // namespace graspkit
