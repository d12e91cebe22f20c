#pragma once
// Time stepping: rigid-body dynamics with contacts, friction, joint limits and DOF controllers.
//
// The formulation is a velocity-level time stepping scheme (Anitescu-Potra, as GraspIt! uses),
// written in generalized coordinates: each graspable body has 6 (the velocity of its centre of
// mass and its angular velocity, world frame), each robot has one per DOF (the DOF's joints move
// rigidly together through their coupling ratios). Robot bases are fixed in the world, or ride
// on the chain they are mounted on; obstacles never move. Each step
//   1. finds the contacts of every nearby pair with the engine's triangle contact search, within
//      a margin that grows with the bodies' speed so that nothing tunnels;
//   2. builds the mass matrix and the free motion (gravity, gyroscopic torques of free bodies,
//      DOF PD controllers with maxEffort, passive joint springs and friction);
//   3. solves the contact and joint-limit impulses as one 3-D friction-contact problem (Coulomb
//      cones, exact, not linearised) with Siconos numerics;
//   4. integrates the poses.
// Units are GraspIt!'s: mm, g, s, so forces are in g*mm/s^2 (1 N = 1e6) and torques in
// g*mm^2/s^2 (1 N*m = 1e9).

#include <functional>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit {

class World;

inline constexpr double kDefaultTimeStep = 0.0025;  // s, GraspIt!'s
inline constexpr double kMaxTimeStep = 0.05;        // s; larger steps are refused
// The smallest step a simulation runs at, s: below it a second takes over a million steps, and a
// dt of 1e-300 would never end.
inline constexpr double kMinTimeStep = 1e-6;
inline constexpr double kStandardGravity = 9810.0;  // mm/s^2

// Contacts settle at half the contact threshold, as GraspIt!'s error correction aims for, so a
// body at rest on another is in contact for the grasp analysis too.
inline constexpr double kRestingSeparation = 0.1;  // mm

// Where a step stops trusting its own result: a body faster than this is a blown-up simulation.
inline constexpr double kRunawaySpeed = 20000.0;       // mm/s
inline constexpr double kRunawayAngularSpeed = 200.0;  // rad/s

struct StepReport {
  double time = 0.0;       // the world's time after the step, s
  int contacts = 0;        // contacts that entered the impulse problem
  int activeContacts = 0;  // those that pushed (normal impulse > 0)
  int jointLimits = 0;     // joint-limit constraints that entered it
  int solverIterations = 0;
  double solverError = 0.0;  // Siconos' residual at the solution
};

// Raised when a step meets a state it cannot continue from: a NaN, a runaway velocity,
// interpenetrating bodies or an impulse problem the solver cannot solve. `state` holds the
// world's full dynamic state before the step as JSON (time, gravity, every body's pose and
// velocity, every robot's DOF values, velocities and targets), enough to reproduce it.
class DynamicsError : public Error {
 public:
  DynamicsError(const std::string& message, std::string state)
      : Error(message), state_(std::move(state)) {}
  const std::string& state() const { return state_; }

 private:
  std::string state_;
};

// Advances `world` by `dt` seconds. Throws graspkit::Error for a dt outside (0, kMaxTimeStep] or
// a dynamic body with a mass or inertia that is not positive; DynamicsError for a bad state.
StepReport step(World& world, double dt = kDefaultTimeStep);

// The dynamic autograsp's set-points (GraspIt!'s): every DOF of `robot` targets the limit its
// default velocity closes towards (a DOF with velocity 0 stays where it is), and its controller's
// set-point moves there at that velocity. Throws graspkit::Error for a bad robot index.
void setClosingTargets(World& world, int robot);

// Sets OpenBLAS, when it is the BLAS behind Siconos, to one thread for the whole process, so that
// the contact problems' products round the same way however many CPUs the process sees (it does
// nothing under another BLAS). step() calls it before its first problem. A program that forks
// workers after loading the engine calls it before the fork: a worker that sets it itself
// restarts OpenBLAS's thread pool, whose threads then spin for ~0.1 s of CPU each.
void useOneBlasThread();

// The world's dynamic state as JSON, as DynamicsError carries it.
std::string dynamicStateJson(const World& world);

struct SimulateRequest {
  double seconds = 1.0;
  double dt = kDefaultTimeStep;
  // Called after every step; returning false stops the simulation early.
  std::function<bool(const World&, const StepReport&)> onStep;
};

struct SimulateResult {
  int steps = 0;
  double time = 0.0;  // the world's time at the end, s
  bool stoppedEarly = false;
  StepReport last;
};

// Steps `world` for `request.seconds`. Throws graspkit::Error for a dt outside [kMinTimeStep,
// kMaxTimeStep]; other errors propagate as from step().
SimulateResult simulate(World& world, const SimulateRequest& request);

}  // namespace graspkit
