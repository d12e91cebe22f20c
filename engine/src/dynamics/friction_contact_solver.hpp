#pragma once
// The one place that talks to Siconos numerics: a 3-D friction-contact problem in its reduced
// (Delassus) form, solved for the impulses. Each constraint has 3 rows (normal, then two
// tangents); its velocity is u = W r + q, and the law is Coulomb's with coefficient mu:
// 0 <= u_n + mu |u_t|  complementary to  r_n >= 0, |r_t| <= mu r_n, with sliding opposing u_t.
// A constraint with mu = 0 is a frictionless unilateral one (joint limits use that).

#include "dynamics/generalized_coordinates.hpp"

namespace graspkit::dynamics {

struct FrictionContactSolution {
  VectorX reaction;  // impulses, 3 per constraint
  VectorX velocity;  // u = W r + q
  int iterations = 0;
  double error = 0.0;  // Siconos' relative residual
  bool solved = false;
  const char* solver = "";
};

// Nonsmooth Gauss-Seidel first (fast and robust on the small, well-conditioned problems of
// grasping); where it does not converge, Alart-Curnier's nonsmooth Newton method.
FrictionContactSolution solveFrictionContact(const MatrixX& W, const VectorX& q, const VectorX& mu,
                                             double tolerance = 1e-10);

}  // namespace graspkit::dynamics
