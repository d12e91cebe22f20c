#pragma once
// Nonnegative least squares: the x >= 0 that minimizes |A x - b|, by Lawson and Hanson's
// active-set method (Solving Least Squares Problems, 1974, chapter 23). It ends after finitely
// many steps with the exact minimizer (up to rounding), so it also answers the feasibility
// question "is b a nonnegative combination of A's columns?": exactly when the residual is 0.
// The statics of a grasp ask it that way (dynamics/static_hold.hpp), with friction cones as
// combinations of their edges.

#include <Eigen/Dense>

namespace graspkit {

struct NonnegativeLeastSquaresRequest {
  // Stop as soon as |A x - b| is at most this (0: run to the minimizer).
  double enoughResidual = 0.0;
  // Outer iterations at most, as a multiple of A's columns (each adds one column to the active
  // set; the method needs about as many as the solution's nonzeros).
  int iterationsPerColumn = 3;
};

struct NonnegativeLeastSquaresResult {
  Eigen::VectorXd x;       // >= 0
  double residual = 0.0;   // |A x - b|
  int iterations = 0;      // outer iterations taken
  bool converged = false;  // the minimizer (or a residual within enoughResidual) was reached
};

NonnegativeLeastSquaresResult nonnegativeLeastSquares(
    const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
    const NonnegativeLeastSquaresRequest& request = {});

}  // namespace graspkit
