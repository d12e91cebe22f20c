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

// Siconos' nonsmooth Gauss-Seidel (NSGS) with its default one-contact Newton solver. Measured
// here on barrettGlassDyn and the mug grasps: it converges in tens to hundreds of sweeps, while
// the global nonsmooth Newton (NSN-AC) fails to factorise the rank-deficient Delassus matrices
// of rigid bodies with more than 3 contacts.
// `start` is the first guess of the reactions (a warm start from the last step), zero if empty.
// At most `max_iterations` sweeps; a solution short of the tolerance is still accepted when its
// residual is below 1e-5.
FrictionContactSolution solveFrictionContact(const MatrixX& W, const VectorX& q, const VectorX& mu,
                                             const VectorX& start = {}, double tolerance = 1e-8,
                                             int max_iterations = 5000);

}  // namespace graspkit::dynamics
