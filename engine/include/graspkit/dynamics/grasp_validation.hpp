#pragma once
// Physical validation of a grasp, as grasp datasets label grasps: the hand squeezes with its DOF
// controllers and the object's weight is turned along each of the 6 axis directions in turn; the
// grasp holds a direction when the object stays with the hand.

#include <array>
#include <string>
#include <vector>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/dynamics/static_hold.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit {

class World;

struct ValidationRequest {
  double seconds = 2.0;  // per direction
  double dt = kDefaultTimeStep;
  // The squeeze settles without gravity before any direction is tried, until the hand and the
  // object are at rest (as below), at most this long. The fingers close on: a breakaway finger's
  // distal link keeps turning to its limit at the DOF's speed (Barrett: about 1.5 s), and a pull
  // that began while they moved could not end at rest before they stopped, so every held
  // direction ran its whole time. The settle ends at rest whatever stopAtRest says, so that a
  // run with stopAtRest false tries each direction from the same squeeze. It also ends once
  // nothing touches the object and the hand's DOFs are still (as below) for restSeconds: a
  // finger that missed can knock the object, which then drifts on and never comes to rest.
  double settleSeconds = 2.0;
  double maxSlip = 5.0;                              // mm, the object's travel relative to the palm
  double maxTurn = 15.0 * 3.14159265358979 / 180.0;  // rad
  double gravity = kStandardGravity;                 // mm/s^2, the size of the pull
  // A direction ends early once the hand and the object have come to rest under the pull:
  // every speed below restSpeed (mm/s; rad/s times the object's radius) and each pair of
  // bodies' force steady for restSeconds or, where a rigid squeeze's force wanders, the speed
  // gaining too slowly to reach restSpeed within `seconds` for at least 0.5 s. What is left of
  // the run cannot move the object by more than restSpeed times the time left, which is counted
  // in its slip. False runs every second.
  bool stopAtRest = true;
  double restSpeed = 1e-3;
  double restSeconds = 0.1;
  // False: the validation ends at the first direction the grasp lets go, and the directions
  // not run to their end are not tried (their results say tried = false). The six pulls then
  // share the steps, a few at a time, the one whose object is moving out fastest first, so that
  // a grasp that fails seldom pays for the pulls it holds. Each pull's run does not depend on
  // the others, so a direction tried gives bit for bit what allDirections gives, and the label
  // `held` (every direction held) is the same either way: a grasp not held has exactly one
  // direction tried and let go. Datasets, where most planned grasps fail, take this
  // (dataset_planning.hpp).
  bool allDirections = true;
  // True: after the squeeze settles at rest, a direction whose pull statics shows the grasp can
  // bear (dynamics/static_hold.hpp: an equilibrium with the DOFs' forces unchanged, within
  // staticsMargins) is labelled held without simulating it; the others are simulated as ever.
  // Statics only ever says held, so a grasp it cannot judge costs what it did.
  bool statics = false;
  StaticHoldMargins staticsMargins;
  // A direction statics shows held is simulated this long all the same (a probe: an edge or a
  // corner the squeeze pinches can turn out of its equilibrium at once), and labelled held
  // there if the object stayed within this share of maxSlip and maxTurn; else it runs on as any.
  double staticsProbeSeconds = 0.025;
  double staticsProbeShare = 0.02;
};

struct DirectionResult {
  Vector3 direction = Vector3::Zero();  // unit, world frame
  bool held = false;
  double slip = 0.0;       // mm: the largest displacement from the palm seen in the direction's run
  double turn = 0.0;       // rad: the largest rotation relative to the palm
  double seconds = 0.0;    // simulated: less than asked when it ended at rest or let go
  std::string failure;     // a DynamicsError's message, when the simulation itself failed
  bool tried = true;       // false: another direction let go first, and allDirections was false
  bool byStatics = false;  // held by statics (ValidationRequest::statics) after its probe
};

struct ValidationResult {
  std::array<DirectionResult, 6> directions;  // +x, -x, +y, -y, +z, -z
  bool held = false;                          // every direction held
  int directionsHeld = 0;                     // of the directions tried
  double settleSeconds = 0.0;                 // simulated: the squeeze before the pulls
};

// Validates the grasp of body `object` by robot `robot` as `world` stands (the hand closed on
// it). The world is not changed: each direction runs on a clone that keeps only the robots and
// the object (obstacles and other bodies are left out, so that nothing but the hand can hold
// it). The hand's DOFs target their closing limits from the closed posture, so each controller
// squeezes with up to its maxEffort. Throws graspkit::Error for bad indices or a request
// outside its ranges.
ValidationResult validateGrasp(const World& world, int robot, int object,
                               const ValidationRequest& request = {});

// validateGrasp() on each world (the same robot and object indices in each: a plan's grasp
// worlds), up to `threads` at a time. Each grasp's result is what validateGrasp() alone gives.
std::vector<ValidationResult> validateGrasps(const std::vector<World>& worlds, int robot,
                                             int object, const ValidationRequest& request = {},
                                             int threads = 1);

}  // namespace graspkit
