#include "graspkit/dynamics/grasp_validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <thread>

#include "graspkit/base/parallel_for.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

namespace {

void checkRequest(const ValidationRequest& request) {
  const auto positive = [](double value) { return std::isfinite(value) && value > 0.0; };
  if (!positive(request.seconds) || !positive(request.maxSlip) || !positive(request.maxTurn) ||
      !positive(request.gravity) || !positive(request.restSpeed) ||
      !(std::isfinite(request.restSeconds) && request.restSeconds >= 0.0) ||
      !(std::isfinite(request.settleSeconds) && request.settleSeconds >= 0.0)) {
    throw Error("grasp validation: seconds, slip, turn and gravity must be positive numbers");
  }
  if (!(request.dt >= kMinTimeStep && request.dt <= kMaxTimeStep)) {
    throw Error(fmt::format("grasp validation: time step {} s is outside [{}, {}] s", request.dt,
                            kMinTimeStep, kMaxTimeStep));
  }
}

// The world with only its robots and the object (index 0 afterwards), everything at rest, the
// hand squeezing towards its closing limits.
World validationWorld(const World& world, int robot, int object) {
  World base = world.clone();
  for (int b = static_cast<int>(base.bodies().size()) - 1; b >= 0; --b) {
    if (b != object) base.removeBody(b);
  }
  base.bodies()[0].state.v.setZero();
  for (int r = 0; r < base.robotCount(); ++r) {
    const std::vector<double> rest(base.robot(r).dofCount(), 0.0);
    base.setDofVelocities(r, rest);
    base.setDofReferences(r, {});
    base.setDofTargets(r, {});
  }
  setClosingTargets(base, robot);
  base.setTime(0.0);
  return base;
}

// The object's pose in the palm's frame.
Transform heldPose(const World& world, int robot) {
  return world.robot(robot).pose().inverse() * world.bodies()[0].pose;
}

// Whether the hand and the object have come to rest: the object, the hand's DOFs and the contact
// impulses unchanged (within restSpeed) for restSeconds.
class RestWatch {
 public:
  RestWatch(const ValidationRequest& request, double radius)
      : request_(request), radius_(std::max(radius, 1.0)) {}
  double radius() const { return radius_; }

  bool atRest(const World& world, int robot) {
    const Body& object = world.bodies()[0];
    double speed = object.state.v.head<3>().norm() + radius_ * object.state.v.tail<3>().norm();
    for (double v : world.robot(robot).dofVelocities())
      speed = std::max(speed, radius_ * std::abs(v));
    const std::vector<ContactImpulse>& impulses = world.lastImpulses();
    if (speed > request_.restSpeed || !sameImpulses(impulses)) {
      since_ = world.time();
      impulses_ = impulses;
      return false;
    }
    return world.time() - since_ >= request_.restSeconds - 1e-9;
  }

 private:
  // The same contacts with the same impulses (1e-6 of the largest) as when the rest began.
  bool sameImpulses(const std::vector<ContactImpulse>& now) const {
    if (now.size() != impulses_.size()) return false;
    double largest = 0.0;
    for (const ContactImpulse& c : impulses_) largest = std::max(largest, c.impulse.norm());
    for (std::size_t i = 0; i < now.size(); ++i) {
      if (!(now[i].body1 == impulses_[i].body1) || !(now[i].body2 == impulses_[i].body2) ||
          (now[i].impulse - impulses_[i].impulse).norm() > 1e-6 * largest)
        return false;
    }
    return true;
  }

  const ValidationRequest& request_;
  double radius_;
  double since_ = -1.0;
  std::vector<ContactImpulse> impulses_;
};

}  // namespace

ValidationResult validateGrasp(const World& world, int robot, int object,
                               const ValidationRequest& request) {
  checkRequest(request);
  world.robot(robot);  // throws for a bad index
  if (object < 0 || object >= static_cast<int>(world.bodies().size()) ||
      !world.bodies()[object].isDynamic()) {
    throw Error(
        fmt::format("grasp validation: body {} is not a graspable body of the world", object));
  }
  ValidationResult result;
  const Vector3 axes[6] = {Vector3::UnitX(),  -Vector3::UnitX(), Vector3::UnitY(),
                           -Vector3::UnitY(), Vector3::UnitZ(),  -Vector3::UnitZ()};
  World base = validationWorld(world, robot, object);
  std::string settle_failure;
  try {
    base.setGravity(Vector3::Zero());
    simulate(base, {.seconds = request.settleSeconds, .dt = request.dt});
  } catch (const DynamicsError& error) {
    settle_failure = error.what();
  }
  const Transform held = heldPose(base, robot);
  for (int k = 0; k < 6; ++k) {
    DirectionResult& direction = result.directions[k];
    direction.direction = axes[k];
    if (!settle_failure.empty()) {
      direction.failure = settle_failure;
      continue;
    }
    World trial = base.clone();
    trial.setGravity(request.gravity * axes[k]);
    RestWatch rest(request, base.bodies()[0].model->maxRadius);
    const auto measure = [&](const World& w, const StepReport&) {
      const Transform now = heldPose(w, robot);
      direction.slip = std::max(direction.slip, (now.translation() - held.translation()).norm());
      direction.turn = std::max(
          direction.turn, Quaternion(now.linear()).angularDistance(Quaternion(held.linear())));
      direction.seconds = w.time() - base.time();
      // Once it has let go, the rest of the run cannot bring it back within the limits.
      if (direction.slip > request.maxSlip || direction.turn > request.maxTurn) return false;
      if (!request.stopAtRest || !rest.atRest(w, robot)) return true;
      // At rest: what is left of the run could move it by restSpeed times the time left at most.
      const double left = request.seconds - direction.seconds;
      direction.slip += request.restSpeed * left;
      direction.turn += request.restSpeed / rest.radius() * left;
      return false;
    };
    try {
      simulate(trial, {.seconds = request.seconds, .dt = request.dt, .onStep = measure});
      direction.held = direction.slip <= request.maxSlip && direction.turn <= request.maxTurn;
    } catch (const DynamicsError& error) {
      direction.failure = error.what();
    }
    if (direction.held) ++result.directionsHeld;
  }
  result.held = result.directionsHeld == 6;
  return result;
}

std::vector<ValidationResult> validateGrasps(const std::vector<World>& worlds, int robot,
                                             int object, const ValidationRequest& request,
                                             int threads) {
  std::vector<ValidationResult> results(worlds.size());
  if (worlds.empty()) return results;
  parallelFor({.end = static_cast<std::int64_t>(worlds.size()), .threads = threads},
              [&](int, std::int64_t i) {
                const auto at = static_cast<std::size_t>(i);
                results[at] = validateGrasp(worlds[at], robot, object, request);
              });
  return results;
}

}  // namespace graspkit
