#include "dynamics/friction_contact_solver.hpp"

#include "graspkit/base/error.hpp"

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <NumericsVerbose.h>
#include <SolverOptions.h>

#include <memory>

namespace graspkit::dynamics {

namespace {

constexpr double kAcceptableError = 1e-5;

struct OptionsDeleter {
  void operator()(SolverOptions* options) const { solver_options_delete(options); }
};

// Runs one Siconos solver on the problem; the problem's arrays stay owned by the caller.
bool runSolver(int solver_id, int max_iterations, double tolerance, MatrixX& W, VectorX& q,
               VectorX& mu, const VectorX& start, FrictionContactSolution& solution) {
  const int rows = static_cast<int>(q.size());
  NumericsMatrix* matrix = NM_create_from_data(NM_DENSE, rows, rows, W.data());
  FrictionContactProblem problem{};
  problem.dimension = 3;
  problem.numberOfContacts = rows / 3;
  problem.M = matrix;
  problem.q = q.data();
  problem.mu = mu.data();
  std::unique_ptr<SolverOptions, OptionsDeleter> options(solver_options_create(solver_id));
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
  options->dparam[SICONOS_DPARAM_TOL] = tolerance;
  // The residual from incremental updates, the full one only to confirm convergence: the full
  // one each sweep costs a product with W per contact.
  options->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] =
      SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_LIGHT_WITH_FULL_FINAL;
  solution.reaction = start.size() == rows ? start : VectorX::Zero(rows);
  solution.velocity = VectorX::Zero(rows);
  const int info =
      fc3d_driver(&problem, solution.reaction.data(), solution.velocity.data(), options.get());
  solution.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  solution.error = options->dparam[SICONOS_DPARAM_RESIDU];
  NM_free_not_dense(matrix);
  return info == 0 && solution.reaction.allFinite();
}

}  // namespace

FrictionContactSolution solveFrictionContact(const MatrixX& W_in, const VectorX& q_in,
                                             const VectorX& mu_in, const VectorX& start,
                                             double tolerance, int max_iterations) {
  FrictionContactSolution solution;
  if (q_in.size() == 0) {
    solution.solved = true;
    return solution;
  }
  numerics_set_verbose(0);
  // Siconos asserts (and aborts the process) on some non-finite problems: never hand it one.
  if (!W_in.allFinite() || !q_in.allFinite() || !mu_in.allFinite() || !start.allFinite())
    throw Error(
        "the contact problem holds a number that is not finite (a body's mass or "
        "inertia, or a velocity, out of range)");
  // Siconos takes non-const pointers; it reads them only.
  MatrixX W = W_in;
  VectorX q = q_in;
  VectorX mu = mu_in;
  solution.solver = "NSGS";
  solution.solved =
      runSolver(SICONOS_FRICTION_3D_NSGS, max_iterations, tolerance, W, q, mu, start, solution);
  // Short of the tolerance, an answer whose residual is small is still good: Siconos' error is
  // relative to the problem's scale.
  if (!solution.solved) {
    solution.solved = solution.reaction.allFinite() && solution.error < kAcceptableError;
  }
  return solution;
}

}  // namespace graspkit::dynamics
