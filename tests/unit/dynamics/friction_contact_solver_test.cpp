// The friction-contact solver (dynamics/friction_contact_solver.hpp) on a rigid block resting on
// three contacts under its weight, with many more contacts around its sides. The three supports
// (frictionless) share the weight as a tripod does: their normal impulses balance the weight's
// impulse and its moments about the block's centre, which fixes them (tripodImpulses, a hand
// computation). Side contacts with room to spare must carry nothing. The solver first solves the
// contacts likely to push (the warm start's, or else those closing) and then adds any it left
// closing: from every warm start it must end at the tripod's impulses, and agree with the whole
// problem solved as one.

#include "dynamics/friction_contact_solver.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "graspkit/dynamics/dynamics.hpp"
#include "test_paths.hpp"

namespace graspkit::dynamics {
namespace {

using Twist = Eigen::Matrix<double, 6, 1>;  // (v, w)

constexpr double kMass = 2.0;      // kg
constexpr double kStep = 0.01;     // s
constexpr double kGravity = 9.81;  // m/s^2
const Vector3 kInertia{0.02, 0.03, 0.04};
// Below the centre, which lies inside their triangle.
const std::vector<Vector3> kSupports = {
    {0.05, 0.0, -0.02}, {-0.03, 0.04, -0.02}, {-0.02, -0.05, -0.02}};

// The rows of a contact at p (block frame, from its centre) with normal n into the block:
// normal and two tangents of the point's velocity v + w x p.
Eigen::Matrix<double, 3, 6> contactRows(const Vector3& p, const Vector3& n) {
  const Vector3 t1 = n.unitOrthogonal();
  const Vector3 directions[3] = {n, t1, n.cross(t1)};
  Eigen::Matrix<double, 3, 6> rows;
  for (int k = 0; k < 3; ++k) {
    rows.block<1, 3>(k, 0) = directions[k].transpose();
    rows.block<1, 3>(k, 3) = p.cross(directions[k]).transpose();
  }
  return rows;
}

struct SideContact {
  Vector3 point, normal;
  double room;  // added to q_n: how fast the step may close it, m/s
};

struct Problem {
  MatrixX W;
  VectorX q, mu;
};

// The supports (mu 0.5) then the side contacts (mu 0.5), for a block whose free motion over the
// step is `free` (v, w) plus the weight's impulse.
Problem block(const std::vector<SideContact>& sides, const Twist& free) {
  const int count = 3 + static_cast<int>(sides.size());
  MatrixX G(3 * count, 6);
  VectorX room = VectorX::Zero(3 * count);
  for (int s = 0; s < 3; ++s) G.middleRows<3>(3 * s) = contactRows(kSupports[s], Vector3::UnitZ());
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const int row = 3 * (3 + static_cast<int>(k));
    G.middleRows<3>(row) = contactRows(sides[k].point, sides[k].normal);
    room[row] = sides[k].room;
  }
  Twist inverse_mass;
  inverse_mass << Vector3::Constant(1.0 / kMass), kInertia.cwiseInverse();
  Twist motion = free;
  motion[2] -= kGravity * kStep;
  return {G * inverse_mass.asDiagonal() * G.transpose(), G * motion + room,
          VectorX::Constant(count, 0.5)};
}

// `count` side contacts around the block at its centre's height, each with 1 m/s of room.
std::vector<SideContact> roomySides(int count) {
  std::vector<SideContact> sides;
  for (int k = 0; k < count; ++k) {
    const double angle = 2.0 * M_PI * (k + 0.5) / count;
    const Vector3 n(-std::cos(angle), -std::sin(angle), 0.0);
    sides.push_back({-0.1 * n + Vector3(0, 0, 0.01 * (k % 3)), n, 1.0});
  }
  return sides;
}

// sum r = m g h; sum r x = 0; sum r y = 0 (moments of the vertical impulses about the centre).
Vector3 tripodImpulses() {
  Matrix3 A;
  for (int s = 0; s < 3; ++s) A.col(s) << 1.0, kSupports[s].x(), kSupports[s].y();
  return A.fullPivLu().solve(Vector3(kMass * kGravity * kStep, 0.0, 0.0));
}

TEST(FrictionContactSolver, ATripodAmongManyContactsCarriesTheWeightAsByHand) {
  // Frictionless supports: with friction, internal forces between them (at no net wrench) would
  // admit many answers.
  Problem problem = block(roomySides(21), Twist::Zero());
  problem.mu.head(3).setZero();
  const Vector3 tripod = tripodImpulses();
  ASSERT_GT(tripod.minCoeff(), 0.0);
  const double scale = tripod.sum();
  const auto rows = problem.q.size();
  // Warm starts: none; the first support alone; the first two; a side contact.
  std::vector<VectorX> starts(4, VectorX::Zero(rows));
  starts[0] = VectorX();
  starts[1][0] = tripod[0];
  starts[2][0] = tripod[0];
  starts[2][3] = tripod[1];
  starts[3][3 * 10] = 0.05;
  const FrictionContactSolution whole = solveFrictionContact(
      problem.W, problem.q, problem.mu, {}, 1e-12, 5000, ContactSolverMethod::GaussSeidel);
  ASSERT_TRUE(whole.solved);
  for (std::size_t k = 0; k < starts.size(); ++k) {
    SCOPED_TRACE(k);
    const FrictionContactSolution s =
        solveFrictionContact(problem.W, problem.q, problem.mu, starts[k], 1e-12);
    ASSERT_TRUE(s.solved);
    EXPECT_LE(s.error, 1e-12);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(s.reaction[3 * c], tripod[c], 1e-9 * scale);
      EXPECT_NEAR(s.reaction.segment<2>(3 * c + 1).norm(), 0.0, 1e-9 * scale);
      EXPECT_NEAR(s.velocity[3 * c], 0.0, 1e-9);  // at rest on its supports
    }
    EXPECT_NEAR(s.reaction.tail(rows - 9).cwiseAbs().maxCoeff(), 0.0, 1e-12);
    for (int c = 3; 3 * c < rows; ++c) EXPECT_NEAR(s.velocity[3 * c], 1.0, 1e-9);
    EXPECT_LE((s.reaction - whole.reaction).norm(), 1e-9 * scale);
    EXPECT_LE((s.velocity - whole.velocity).norm(), 1e-9);
  }
}

// The block also slides towards -x at 0.2 m/s, into a wall contact with no room at its centre's
// height, and the supports are frictionless. Warm-started with the supports alone, the first
// answer leaves the wall closing: it must join, take the sliding momentum m v (no moment about
// the centre) and stop the block, the tripod still carrying the weight.
TEST(FrictionContactSolver, AContactLeftClosingJoinsAndStopsTheBlock) {
  std::vector<SideContact> sides = roomySides(20);
  sides.insert(sides.begin(), SideContact{{-0.1, 0.0, 0.0}, Vector3::UnitX(), 0.0});
  Twist sliding = Twist::Zero();
  sliding[0] = -0.2;
  Problem problem = block(sides, sliding);
  problem.mu.head(4).setZero();
  const Vector3 tripod = tripodImpulses();
  VectorX start = VectorX::Zero(problem.q.size());
  for (int s = 0; s < 3; ++s) start[3 * s] = tripod[s];
  const FrictionContactSolution s =
      solveFrictionContact(problem.W, problem.q, problem.mu, start, 1e-12);
  ASSERT_TRUE(s.solved);
  EXPECT_NEAR(s.reaction[9], kMass * 0.2, 1e-9);
  EXPECT_NEAR(s.velocity[9], 0.0, 1e-9);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.reaction[3 * c], tripod[c], 1e-9 * tripod.sum());
  EXPECT_NEAR(s.reaction.tail(s.reaction.size() - 12).cwiseAbs().maxCoeff(), 0.0, 1e-12);
}

// A batch forks a worker per object. OpenBLAS shuts its thread pool down at a fork, and its
// thread setter restarts the pool in the child, whose threads then spin for a tenth of a second
// of CPU each: set in the parent before the fork, the worker solves on its one thread and never
// starts them. (With one CPU, or another BLAS, there are no threads to start.)
TEST(FrictionContactSolver, AWorkerForkedAfterTheBlasSettingStartsNoThreads) {
  useOneBlasThread();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const Problem problem = block(roomySides(21), Twist::Zero());
    const FrictionContactSolution s =
        solveFrictionContact(problem.W, problem.q, problem.mu, {}, 1e-12);
    const auto threads = std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                                       std::filesystem::directory_iterator{});
    ::_exit(s.solved ? static_cast<int>(std::min<std::ptrdiff_t>(threads, 100)) : 101);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1) << "threads in the worker (101: the problem was not solved)";
}

// A real squeeze that stalls (stalled_squeeze.txt): uFactory's xArm gripper closed on a generated
// object under validation, where Newton's method fails and NSGS, from its answer, stalls a little
// above the tolerance. The finishing sweeps end once a round of them stops halving the residual
// within 1e-5, well short of their limit, and the answer must meet Coulomb's law on its own
// terms, checked here from W and q rather than by Siconos' residual: impulses inside the cones,
// contacts not closing, and no push where a contact opens.
TEST(FrictionContactSolver, AStalledSqueezeEndsEarlyWithinCoulombsLaw) {
  std::ifstream in(test::sourceDir() / "tests/unit/dynamics/stalled_squeeze.txt");
  ASSERT_TRUE(in) << "tests/unit/dynamics/stalled_squeeze.txt is missing";
  std::string line;
  while (in.peek() == '#') std::getline(in, line);
  int count = 0, max_iterations = 0;
  double tolerance = 0.0;
  in >> count >> tolerance >> max_iterations;
  const int rows = 3 * count;
  MatrixX W(rows, rows);
  VectorX q(rows), mu(count), start(rows);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < rows; ++j) in >> W(i, j);
  for (int i = 0; i < rows; ++i) in >> q[i];
  for (int i = 0; i < count; ++i) in >> mu[i];
  for (int i = 0; i < rows; ++i) in >> start[i];
  ASSERT_TRUE(in) << "stalled_squeeze.txt ends early";

  const FrictionContactSolution s =
      solveFrictionContact(W, q, mu, start, tolerance, max_iterations);
  ASSERT_TRUE(s.solved);
  EXPECT_GT(s.error, tolerance);  // it stalls: the rule under test decided where it ended
  EXPECT_LT(s.error, 1e-5);
  EXPECT_LT(s.iterations, max_iterations / 2);
  // Coulomb's law, to a small share of the problem's scale: the largest impulse and |q|.
  const VectorX u = W * s.reaction + q;
  const double impulse = s.reaction.cwiseAbs().maxCoeff();
  const double speed = q.cwiseAbs().maxCoeff();
  ASSERT_GT(impulse, 0.0);
  for (int c = 0; c < count; ++c) {
    SCOPED_TRACE(c);
    const double normal = s.reaction[3 * c];
    EXPECT_GE(normal, -1e-6 * impulse);
    EXPECT_LE(s.reaction.segment<2>(3 * c + 1).norm(), mu[c] * normal + 1e-6 * impulse);
    EXPECT_GE(u[3 * c], -1e-4 * speed);  // not closing
    // A contact that opens pushes with nothing.
    if (u[3 * c] > 1e-3 * speed) EXPECT_LE(normal, 1e-4 * impulse);
  }
}

}  // namespace
}  // namespace graspkit::dynamics
