#include "dynamics/friction_contact_solver.hpp"

#include "graspkit/dynamics/dynamics.hpp"

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

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

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

namespace graspkit {

// OpenBLAS (Debian's BLAS, behind Siconos) splits a product over threads of its own when it sees
// more than one CPU, and the partial sums then round differently: a dataset's files came out
// different under mpirun, where each rank is bound to one core, than from one process, and a
// squeezed grasp's slips differed in the last digits. These problems are far too small to gain
// from threads, so OpenBLAS is set to one thread before the first contact problem is solved
// (process-wide: OpenBLAS 0.3.21 has no per-thread setting). Another BLAS has no such function,
// and there is nothing to do. The flag is copied into a forked child, which then leaves OpenBLAS
// alone: its setter would first restart the thread pool the fork shut down.
void useOneBlasThread() {
  static std::once_flag once;
  std::call_once(once, [] {
    using SetThreads = void (*)(int);
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      set(1);
  });
}

}  // namespace graspkit

namespace graspkit::dynamics {

namespace {

constexpr double kAcceptableError = 1e-5;
// NSGS sweeps before Newton's method takes over from NSGS's answer.
constexpr int kSweepsBeforeNewton = 100;
// Problems of this many contacts or more are sifted (solveFrictionContact); below, whole.
constexpr int kSiftedContacts = 8;
// Rounds of sifting before the whole problem is solved.
constexpr int kSiftRounds = 4;

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

// NSGS's last sweeps after Newton's method, in rounds. Most squeezes they finish within a few
// hundred sweeps; the rest stall a little above the tolerance, and used to run all their sweeps
// (4,900) for an answer within kAcceptableError anyway: a fifth of an xArm gripper's batch. A
// round that leaves the residual within kAcceptableError and has not halved it ends them there.
// Whether the problem is solved (to the tolerance).
bool finishSweeps(MatrixX& W, VectorX& q, VectorX& mu, const VectorX& start, double tolerance,
                  int max_sweeps, FrictionContactSolution& solution) {
  constexpr int kRound = 100;
  constexpr double kStalled = 0.5;
  VectorX from = start;
  int done = 0;
  double previous = std::numeric_limits<double>::infinity();
  bool solved = false;
  for (int left = max_sweeps; left > 0;) {
    const int round = std::min(left, kRound);
    solved = runSolver(SICONOS_FRICTION_3D_NSGS, round, tolerance, W, q, mu, from, solution,
                       SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL);
    done += solution.iterations;
    left -= round;
    if (solved || !solution.reaction.allFinite()) break;
    if (solution.error < kAcceptableError && solution.error > kStalled * previous) break;
    previous = solution.error;
    from = solution.reaction;
  }
  solution.iterations = done;
  return solved;
}

// The problem as a whole: NSGS, then Newton and NSGS again where it is slow (the header).
FrictionContactSolution solveWhole(const MatrixX& W_in, const VectorX& q_in, const VectorX& mu_in,
                                   const VectorX& start, double tolerance, int max_iterations,
                                   ContactSolverMethod method) {
  FrictionContactSolution solution;
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
      finishSweeps(W, q, mu, finish, tolerance, max_iterations - first_sweeps, solution);
  solution.iterations += sweeps;
  // Short of the tolerance, an answer whose residual is small is still good: Siconos' error is
  // relative to the problem's scale.
  if (!solution.solved) {
    solution.solved = solution.reaction.allFinite() && solution.error < kAcceptableError;
  }
  return solution;
}

// The contacts likely to push: those the warm start pushes with or, where it pushes with none,
// those whose free motion closes them (q_n < 0). Closing contacts are a poor guess when the warm
// start knows better: inside a squeeze nearly every contact closes (27 of a UMI grasp's 28) and
// a few push (4).
std::vector<int> likelyPushing(const VectorX& q, const VectorX& start) {
  std::vector<int> contacts;
  if (start.size() == q.size())
    for (Eigen::Index c = 0; 3 * c < q.size(); ++c)
      if (start[3 * c] > 0.0) contacts.push_back(static_cast<int>(c));
  if (!contacts.empty()) return contacts;
  for (Eigen::Index c = 0; 3 * c < q.size(); ++c)
    if (q[3 * c] < 0.0) contacts.push_back(static_cast<int>(c));
  return contacts;
}

// The problem restricted to `contacts`, solved as a whole; the reactions and velocities are the
// whole problem's, with no reaction at the other contacts.
FrictionContactSolution solvePart(const MatrixX& W, const VectorX& q, const VectorX& mu,
                                  const VectorX& start, const std::vector<int>& contacts,
                                  double tolerance, int max_iterations,
                                  ContactSolverMethod method) {
  // The part's rows: 3 per contact (normal, then the two tangents).
  std::vector<Eigen::Index> rows;
  for (int c : contacts)
    for (int k = 0; k < 3; ++k) rows.push_back(3 * static_cast<Eigen::Index>(c) + k);
  const MatrixX part_W = W(rows, rows);
  const VectorX part_mu = mu(contacts);
  const VectorX part_start = start.size() == q.size() ? VectorX(start(rows)) : VectorX();
  const VectorX part_q = q(rows);
  // Siconos' residual is relative to |q|: the part is solved to the whole problem's accuracy.
  const double scale = part_q.norm() > 0.0 ? q.norm() / part_q.norm() : 1.0;
  FrictionContactSolution part =
      solveWhole(part_W, part_q, part_mu, part_start, tolerance * scale, max_iterations, method);
  VectorX reaction = VectorX::Zero(q.size());
  reaction(rows) = part.reaction;
  part.reaction = std::move(reaction);
  part.velocity = W * part.reaction + q;
  return part;
}

}  // namespace

// Sifted (the header): the part likely to push, then the contacts its answer leaves closing.
FrictionContactSolution solveFrictionContact(const MatrixX& W, const VectorX& q, const VectorX& mu,
                                             const VectorX& start, double tolerance,
                                             int max_iterations, ContactSolverMethod method) {
  if (q.size() == 0) {
    FrictionContactSolution solution;
    solution.solved = true;
    return solution;
  }
  numerics_set_verbose(0);
  useOneBlasThread();
  // Siconos asserts (and aborts the process) on some non-finite problems: never hand it one.
  if (!W.allFinite() || !q.allFinite() || !mu.allFinite() || !start.allFinite())
    throw Error(
        "the contact problem holds a number that is not finite (a body's mass or "
        "inertia, or a velocity, out of range)");
  const auto count = static_cast<int>(q.size() / 3);
  std::vector<int> contacts = likelyPushing(q, start);
  if (count < kSiftedContacts || static_cast<int>(contacts.size()) == count)
    return solveWhole(W, q, mu, start, tolerance, max_iterations, method);
  VectorX from = start;
  int iterations = 0;
  for (int round = 0; round < kSiftRounds && !contacts.empty(); ++round) {
    FrictionContactSolution part =
        solvePart(W, q, mu, from, contacts, tolerance, max_iterations, method);
    iterations += part.iterations;
    if (!part.solved) break;
    std::vector<bool> in(static_cast<std::size_t>(count), false);
    for (int c : contacts) in[static_cast<std::size_t>(c)] = true;
    std::vector<int> closing;
    for (int c = 0; c < count; ++c)
      if (!in[static_cast<std::size_t>(c)] && part.velocity[3 * c] < 0.0) closing.push_back(c);
    if (closing.empty()) {
      MatrixX whole_W = W;
      VectorX whole_q = q, whole_mu = mu;
      part.error = residual(whole_W, whole_q, whole_mu, part.reaction);
      part.iterations = iterations;
      return part;
    }
    contacts.insert(contacts.end(), closing.begin(), closing.end());
    std::sort(contacts.begin(), contacts.end());
    from = part.reaction;
  }
  FrictionContactSolution solution = solveWhole(W, q, mu, start, tolerance, max_iterations, method);
  solution.iterations += iterations;
  return solution;
}

}  // namespace graspkit::dynamics
