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

enum class ContactSolverMethod { NewtonThenGaussSeidel, GaussSeidel };

// With NewtonThenGaussSeidel, Siconos' global nonsmooth Newton method on the Alart-Curnier function
// (NSN-AC) first, on W with a diagonal of 1e-14 of its largest so that the rank-deficient Delassus
// matrices of rigid bodies with redundant contacts factorise; its answer is kept when its residual
// on the unchanged problem meets the tolerance. Otherwise Siconos' nonsmooth Gauss-Seidel (NSGS)
// with its default one-contact Newton solver. On barrettGlassDyn and the mug grasps NSGS converges
// in tens to hundreds of sweeps, but a grasp squeezed under validation's pull needs its full 5000
// and stops short of 1e-10, where NSN-AC takes about 5 Newton steps (0.07 ms against 19 ms).
// `start` is the first guess of the reactions (a warm start from the last step), zero if empty.
// At most `max_iterations` NSGS sweeps; a solution short of the tolerance is still accepted
// when its residual is below 1e-5.
FrictionContactSolution solveFrictionContact(
    const MatrixX& W, const VectorX& q, const VectorX& mu, const VectorX& start = {},
    double tolerance = 1e-8, int max_iterations = 5000,
    ContactSolverMethod method = ContactSolverMethod::NewtonThenGaussSeidel);

}  // namespace graspkit::dynamics
