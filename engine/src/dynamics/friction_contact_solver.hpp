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

// Siconos' nonsmooth Gauss-Seidel (NSGS) with its default one-contact Newton solver, from
// `start`. With NewtonThenGaussSeidel, when 100 sweeps have not met the tolerance, Siconos'
// global nonsmooth Newton method on the Alart-Curnier function (NSN-AC) goes on from NSGS's
// answer, on W with a diagonal of 1e-14 of its largest so that the rank-deficient Delassus
// matrices of rigid bodies with redundant contacts factorise; its answer is kept when its
// residual on the unchanged problem meets the tolerance and its impulses are of a size the
// problem can ask for; otherwise NSGS goes on to `max_iterations` sweeps in all, from Newton's
// answer when its residual is below 1e-5 (Newton stalls from rounding just short of a tight
// tolerance, and NSGS finishes from there in hundreds of sweeps), else from its own. On
// barrettGlassDyn and the mug grasps NSGS converges in tens to hundreds of sweeps, but a grasp
// squeezed under validation's pull took its whole 5000 and stopped short of 1e-10, where Newton
// needs about 5 iterations. Newton starts from NSGS's answer, not from scratch, because a rigid
// squeeze admits many answers and the one Newton finds from scratch differs from NSGS's enough
// to change which grasps hold: from NSGS's answer it lands on the nearby one (measured on 10
// validated grasps of a generated object: 9 of 10 labels as with NSGS alone, against 8 of 10).
// `start` is the first guess of the reactions (a warm start from the last step), zero if empty.
// At most `max_iterations` NSGS sweeps; a solution short of the tolerance is still accepted
// when its residual is below 1e-5. The sweeps after Newton's method run in rounds of 100, and
// end once a round leaves the residual below 1e-5 without halving it: such a squeeze stalls
// there (an xArm gripper's ran all 4,900 sweeps to end between 1e-9 and 1e-6, a fifth of its
// batch's time). Against running them all, 988 of 1,000 validated grasps kept their label (6
// changed each way), as many as OpenBLAS's AVX2 kernels keep against its AVX-512 ones (984).
//
// Sifted: a problem of 8 contacts or more is first solved on the contacts likely to push (the
// warm start's, or the closing ones where it has none), to the whole problem's accuracy (the
// tolerance scaled by |q| / |q_part|, Siconos' residual being relative to |q|). With no
// reaction at the others, that answer is an answer of the whole problem exactly when it leaves
// every other contact opening (u_n >= 0: Coulomb's law asks no more of a contact that does not
// push, and such a contact adds nothing to the residual). The contacts it leaves closing join
// and the part is solved again from its answer; after 4 rounds, or should a part fail, the
// whole problem is solved as above. The error reported is the residual on the whole problem.
// Why: the dynamics asks for every feature pair within a step's reach, and a squeeze holds many
// that never push. A UMI gripper's grasp under validation had 93 contacts, 14 pushing: NSGS
// took 380 ms for its 5000 sweeps of the whole (that grasp's validation: 1.48 s before, 0.50 s
// sifted). A rigid squeeze admits many answers, and the part's may differ from the whole's
// (they are equally answers): measured on 180 validated grasps (UMI, Barrett, Robotiq 2F-85 on 6
// generated objects), 175 labels came out the same, 4 grasps held that had let go, 1 the other way.
FrictionContactSolution solveFrictionContact(
    const MatrixX& W, const VectorX& q, const VectorX& mu, const VectorX& start = {},
    double tolerance = 1e-8, int max_iterations = 5000,
    ContactSolverMethod method = ContactSolverMethod::NewtonThenGaussSeidel);

}  // namespace graspkit::dynamics
