#include "dynamics/friction_contact_solver.hpp"

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <NumericsVerbose.h>
#include <SolverOptions.h>
#include <fc3d_compute_error.h>

#include <dlfcn.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>

// Siconos 4.4 prints its warnings on standard output whatever its verbosity, where they would
// break a command's --json or CSV output (the library never writes there, see base/log.cpp).
// NSGS warns when its sweeps stop changing the answer short of the tolerance ("tolerance has to
// be positive!!"): it then stops, and the step goes on to Newton's method. A fingertip squeezing
// an object does this a few times per grasp validated. numerics_warning is exported by
// libsiconos_numerics, which calls it through its PLT, but is in none of its installed headers:
// this definition takes its place for the whole process (libgraspkit comes before
// libsiconos_numerics in the order the dynamic linker looks symbols up) and turns the warnings
// into trace lines (graspkit -v).
extern "C" void numerics_warning(const char* function, const char* format, ...) {
  char message[512];
  va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(message, sizeof message, format, arguments);
  va_end(arguments);
  graspkit::trace(std::string("Siconos ") + (function ? function : "") + ": " + message);
}

namespace graspkit::dynamics {

namespace {

constexpr double kAcceptableError = 1e-5;
// NSGS sweeps before Newton's method takes over from NSGS's answer.
constexpr int kSweepsBeforeNewton = 100;

// OpenBLAS (Debian's BLAS, behind Siconos) splits a product over threads of its own when it sees
// more than one CPU, and the partial sums then round differently: a dataset's files came out
// different under mpirun, where each rank is bound to one core, than from one process, and a
// squeezed grasp's slips differed in the last digits. These problems are far too small to gain
// from threads, so OpenBLAS is set to one thread the first time a contact problem is solved
// (process-wide: OpenBLAS 0.3.21 has no per-thread setting). Another BLAS has no such function,
// and there is nothing to do.
void useOneBlasThread() {
  static std::once_flag once;
  std::call_once(once, [] {
    using SetThreads = void (*)(int);
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      set(1);
  });
}

struct OptionsDeleter {
  void operator()(SolverOptions* options) const { solver_options_delete(options); }
};

// Siconos' view of the problem (W, q, mu): it points into the caller's arrays, which it reads.
struct SiconosProblem {
  SiconosProblem(MatrixX& W, VectorX& q, VectorX& mu)
      : matrix(NM_create_from_data(NM_DENSE, static_cast<int>(q.size()), static_cast<int>(q.size()),
                                   W.data())) {
    problem.dimension = 3;
    problem.numberOfContacts = static_cast<int>(q.size()) / 3;
    problem.M = matrix;
    problem.q = q.data();
    problem.mu = mu.data();
  }
  ~SiconosProblem() { NM_free_not_dense(matrix); }
  SiconosProblem(const SiconosProblem&) = delete;
  SiconosProblem& operator=(const SiconosProblem&) = delete;

  NumericsMatrix* matrix;
  FrictionContactProblem problem{};
};

// Runs one Siconos solver on the problem; the problem's arrays stay owned by the caller.
bool runSolver(int solver_id, int max_iterations, double tolerance, MatrixX& W, VectorX& q,
               VectorX& mu, const VectorX& start, FrictionContactSolution& solution,
               int nsgs_error = SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_LIGHT_WITH_FULL_FINAL) {
  const int rows = static_cast<int>(q.size());
  SiconosProblem siconos(W, q, mu);
  std::unique_ptr<SolverOptions, OptionsDeleter> options(solver_options_create(solver_id));
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
  options->dparam[SICONOS_DPARAM_TOL] = tolerance;
  if (solver_id == SICONOS_FRICTION_3D_NSGS) {
    // By default the residual from incremental updates, the full one only to confirm
    // convergence: the full one each sweep costs a product with W per contact.
    options->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = nsgs_error;
  }
  solution.reaction = start.size() == rows ? start : VectorX::Zero(rows);
  solution.velocity = VectorX::Zero(rows);
  const int info = fc3d_driver(&siconos.problem, solution.reaction.data(), solution.velocity.data(),
                               options.get());
  solution.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  solution.error = options->dparam[SICONOS_DPARAM_RESIDU];
  return info == 0 && solution.reaction.allFinite();
}

// Siconos' residual of `reaction` on the problem (W, q, mu), relative to |q| as its solvers
// report it.
double residual(MatrixX& W, VectorX& q, VectorX& mu, VectorX& reaction) {
  SiconosProblem siconos(W, q, mu);
  VectorX velocity = W * reaction + q;
  const double scale = q.norm() > 0.0 ? q.norm() : 1.0;
  double error = 0.0;
  fc3d_compute_error(&siconos.problem, reaction.data(), velocity.data(), 0.0, nullptr, scale,
                     &error);
  return error;
}

// Whether `reaction` is of the size the problem can ask for. Along a near-null direction of a
// singular W (an internal squeeze between rigid contacts) Newton may return impulses 1e10 times
// too large that still meet the residual, and the bodies' velocities, computed from them with
// other rounding, blow up. An impulse that stops each contact's approach on its own
// (|q_n| / W_nn) bounds what a step needs, up to the warm start the squeeze already holds.
bool plausible(const MatrixX& W, const VectorX& q, const VectorX& start, const VectorX& reaction) {
  double bound = start.size() == reaction.size() ? start.cwiseAbs().sum() : 0.0;
  for (Eigen::Index row = 0; row < q.size(); row += 3) {
    if (W(row, row) > 0.0) bound += std::abs(q[row]) / W(row, row);
  }
  constexpr double kSlack = 10.0;
  return reaction.cwiseAbs().maxCoeff() <= kSlack * bound;
}

// The nonsmooth Newton method on the Alart-Curnier function (NSN-AC) from `start`: a few
// iterations where NSGS needs thousands of sweeps on a squeeze (solveFrictionContact's comment).
// Rigid bodies with redundant contacts make W singular, which its LU cannot factorise; a
// diagonal of 1e-14 of W's largest lets it. The solution's error is its residual on the
// unchanged problem (infinite for an answer that is not finite or not plausible), and the answer
// is accepted when that meets the tolerance.
bool runNewton(double tolerance, const MatrixX& W, VectorX& q, VectorX& mu, const VectorX& start,
               FrictionContactSolution& solution) {
  constexpr double kRegularisation = 1e-14;
  constexpr int kNewtonIterations = 100;
  MatrixX regularised = W;
  regularised.diagonal().array() += kRegularisation * W.diagonal().cwiseAbs().maxCoeff();
  runSolver(SICONOS_FRICTION_3D_NSN_AC, kNewtonIterations, tolerance, regularised, q, mu, start,
            solution);
  solution.error = std::numeric_limits<double>::infinity();
  if (!solution.reaction.allFinite() || !plausible(W, q, start, solution.reaction)) return false;
  MatrixX unchanged = W;
  solution.error = residual(unchanged, q, mu, solution.reaction);
  solution.velocity = W * solution.reaction + q;
  return solution.error <= tolerance;
}

}  // namespace

FrictionContactSolution solveFrictionContact(const MatrixX& W_in, const VectorX& q_in,
                                             const VectorX& mu_in, const VectorX& start,
                                             double tolerance, int max_iterations,
                                             ContactSolverMethod method) {
  FrictionContactSolution solution;
  if (q_in.size() == 0) {
    solution.solved = true;
    return solution;
  }
  numerics_set_verbose(0);
  useOneBlasThread();
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
  const int first_sweeps = method == ContactSolverMethod::NewtonThenGaussSeidel
                               ? std::min(max_iterations, kSweepsBeforeNewton)
                               : max_iterations;
  solution.solved =
      runSolver(SICONOS_FRICTION_3D_NSGS, first_sweeps, tolerance, W, q, mu, start, solution);
  if (solution.solved || first_sweeps == max_iterations) {
    if (!solution.solved)
      solution.solved = solution.reaction.allFinite() && solution.error < kAcceptableError;
    return solution;
  }
  // NSGS is slow to finish here: Newton's method from where it got, which converges to the
  // answer near it (among the many a rigid squeeze admits, the one NSGS was heading for).
  const VectorX near = solution.reaction.allFinite() ? VectorX(solution.reaction) : start;
  const int sweeps = solution.iterations;
  if (runNewton(tolerance, W, q, mu, near, solution)) {
    solution.solver = "NSGS+NSN-AC";
    solution.iterations += sweeps;
    solution.solved = true;
    return solution;
  }
  // Newton's iterates on a singular W stall from rounding just short of a tight tolerance
  // (a squeezed box's 622 stalls: half ended below 4e-10 against 1e-10). NSGS finishes from
  // Newton's answer in about 200 sweeps, where from its own it ran nearly all its 5000.
  const VectorX finish = solution.error < kAcceptableError ? VectorX(solution.reaction) : near;
  solution.solver = "NSGS";
  // The full residual each sweep: from Newton's answer the sweeps barely move, and Siconos' light
  // residual (the sweep's change) would read as converged, lower its own tolerance to zero and
  // stop with a warning on stderr.
  solution.solved =
      runSolver(SICONOS_FRICTION_3D_NSGS, max_iterations - first_sweeps, tolerance, W, q, mu,
                finish, solution, SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL);
  solution.iterations += sweeps;
  // Short of the tolerance, an answer whose residual is small is still good: Siconos' error is
  // relative to the problem's scale.
  if (!solution.solved) {
    solution.solved = solution.reaction.allFinite() && solution.error < kAcceptableError;
  }
  return solution;
}

}  // namespace graspkit::dynamics
