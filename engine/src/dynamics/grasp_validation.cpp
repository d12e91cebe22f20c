#include "graspkit/dynamics/grasp_validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <thread>

#include "graspkit/base/parallel_for.hpp"
#include "graspkit/dynamics/static_hold.hpp"
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
  if (!(std::isfinite(request.staticsProbeSeconds) && request.staticsProbeSeconds >= 0.0) ||
      !(request.staticsProbeShare > 0.0 && request.staticsProbeShare <= 1.0)) {
    throw Error(
        "grasp validation: the statics' probe must last 0 s or more, and its share of the "
        "let-go limits be within (0, 1]");
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
  // Grasps saved by earlier builds mark the joints their DOFs stopped with as broken away, which
  // would hold those fingers limp: each DOF drives them, as the autograsp now leaves them.
  base.releaseBreakawayNotLagging(robot);
  base.setTime(0.0);
  return base;
}

// The squeeze settles at least this long before it may end at rest: the controllers' set-points
// start at the closed posture, and the first steps can be still.
constexpr double kMinSettleSeconds = 0.05;

// The object's pose in the palm's frame.
Transform heldPose(const World& world, int robot) {
  return world.robot(robot).pose().inverse() * world.bodies()[0].pose;
}

// The fastest of the hand's DOFs, as the speed of a point `radius` from the joint: the rest
// watches compare it with restSpeed (mm/s), the object's size standing for the lever.
double handSpeed(const World& world, int robot, double radius) {
  double speed = 0.0;
  for (double v : world.robot(robot).dofVelocities()) speed = std::max(speed, radius * std::abs(v));
  return speed;
}

// Whether the hand and the object have come to rest: the object and the hand's DOFs slower than
// restSpeed, and each pair of bodies' force steady, for restSeconds; or, where a pair's force
// has wandered, the speed gaining too slowly to reach restSpeed within a run for 0.5 s.
//
// The force is each pair's total impulse, averaged over the last two steps. Rigid bodies with
// redundant contacts share a force among them in no one way (the solver may pass it from one
// contact to another at rest), and a squeeze whose contacts sit inside the resting separation
// alternates between a step that pushes them out and one that does not, so single contacts'
// impulses at one step never stay within 1e-6 of each other. Measured on a box held by the
// Barrett with every speed below 1e-9 mm/s, a pair's force still moved by up to 3 % from step to
// step; a force that grows by more than 5 % within restSeconds restarts the watch.
//
// A rigid squeeze's internal force is not determined at all: with every speed below 1e-4 mm/s
// and the net force on the object its weight, the solver passed force between the contacts of a
// finger in jumps of more than 5 % every few tenths of a second, and a link touched the object at
// one step and not at the next (the Barrett on a box): the watch never ran out, and every pull
// of a squeezed grasp ran to its end. Such a grasp is taken to be at rest all the same when its
// motion, followed to the end of a run at the rate it gained speed since the watch began, stays
// below restSpeed for kWanderingRestSeconds (0.5 s). Not 0.1 s: a wandering force can still tip
// a grasp into sliding, and one box stood still for 0.3 s before it slid out 0.7 s into its pull.
class RestWatch {
 public:
  RestWatch(const ValidationRequest& request, double radius)
      : request_(request), radius_(std::max(radius, 1.0)) {}
  double radius() const { return radius_; }

  bool atRest(const World& world, int robot) {
    const Body& object = world.bodies()[0];
    const double speed =
        std::max(object.state.v.head<3>().norm() + radius_ * object.state.v.tail<3>().norm(),
                 handSpeed(world, robot, radius_));
    PairForces now = pairForces(world.lastImpulses());
    PairForces mean = now;
    if (!averaged(previous_, mean)) mean.clear();
    previous_ = std::move(now);
    if (!watching_ || speed > request_.restSpeed) {
      restart(world.time(), speed);
      steadySince_ = world.time();
      forces_ = std::move(mean);
      return false;
    }
    if (!steady(mean)) {
      // The steady watch begins again from these forces; the slow one goes on while the speed,
      // gaining at its rate since that watch began, stays below restSpeed for a whole run.
      steadySince_ = world.time();
      forces_ = std::move(mean);
      const double elapsed = world.time() - since_;
      const double gain = elapsed > 0.0 ? std::max(0.0, speed - speedSince_) / elapsed : 0.0;
      if (speed + gain * request_.seconds > request_.restSpeed) {
        restart(world.time(), speed);
        return false;
      }
    }
    return world.time() - steadySince_ >= request_.restSeconds - 1e-9 ||
           world.time() - since_ >= std::max(request_.restSeconds, kWanderingRestSeconds) - 1e-9;
  }

 private:
  using PairForces = std::vector<std::pair<std::pair<BodyRef, BodyRef>, Vector3>>;

  void restart(double time, double speed) {
    watching_ = true;
    since_ = time;
    speedSince_ = speed;
  }

  static PairForces pairForces(const std::vector<ContactImpulse>& impulses) {
    PairForces forces;
    for (const ContactImpulse& c : impulses) {
      if (forces.empty() || !(forces.back().first.first == c.body1) ||
          !(forces.back().first.second == c.body2))
        forces.push_back({{c.body1, c.body2}, Vector3::Zero()});
      forces.back().second += c.impulse;
    }
    return forces;
  }

  // `mean` (this step's forces) becomes the mean with `previous` when both have the same pairs.
  static bool averaged(const PairForces& previous, PairForces& mean) {
    if (previous.size() != mean.size()) return false;
    for (std::size_t i = 0; i < mean.size(); ++i) {
      if (!(previous[i].first == mean[i].first)) return false;
      mean[i].second = 0.5 * (mean[i].second + previous[i].second);
    }
    return true;
  }

  // The same pairs with the same forces (5 % of the largest) as when the rest began.
  bool steady(const PairForces& now) const {
    if (now.size() != forces_.size()) return false;
    double largest = 0.0;
    for (const auto& f : forces_) largest = std::max(largest, f.second.norm());
    for (std::size_t i = 0; i < now.size(); ++i) {
      if (!(now[i].first == forces_[i].first) ||
          (now[i].second - forces_[i].second).norm() > kSteadyForce * largest)
        return false;
    }
    return true;
  }

  static constexpr double kSteadyForce = 0.05;
  static constexpr double kWanderingRestSeconds = 0.5;
  const ValidationRequest& request_;
  double radius_;
  bool watching_ = false;     // a rest has begun
  double since_ = 0.0;        // when every speed went below restSpeed (the slow watch)
  double speedSince_ = 0.0;   // the speed then
  double steadySince_ = 0.0;  // when the pairs' forces were last taken (the steady watch)
  PairForces previous_;
  PairForces forces_;
};

// The squeeze's other way to rest: the object touches nothing and the hand is still. A grasp
// that missed closes the fingers beside the object, or on each other, and a finger brushing past
// can knock the object, which then drifts on at a steady speed (the squeeze has no gravity):
// its speed never falls below restSpeed, and the settle ran its whole time (the Robotiq 2F-85
// on a convex hull: 800 steps of pads pressed on each other, over 2 minutes of CPU a grasp).
// Nothing is left to settle once no contact involves the object and every DOF is slower than
// restSpeed for restSeconds; the pulls then start with the object moving as it is.
class FreeObjectWatch {
 public:
  explicit FreeObjectWatch(const ValidationRequest& request, double radius)
      : request_(request), radius_(std::max(radius, 1.0)) {}

  bool atRest(const World& world, int robot) {
    const BodyRef object = BodyRef::body(0);
    bool still = true;
    for (const ContactImpulse& c : world.lastImpulses())
      if (c.body1 == object || c.body2 == object) still = false;
    if (handSpeed(world, robot, radius_) > request_.restSpeed) still = false;
    if (!still) {
      since_.reset();
      return false;
    }
    if (!since_) since_ = world.time();
    return world.time() - *since_ >= request_.restSeconds - 1e-9;
  }

 private:
  const ValidationRequest& request_;
  double radius_;
  std::optional<double> since_;  // when the object was last seen free and the hand still
};

// One direction's pull: the settled squeeze with the weight turned along `axis`, stepped as
// simulate() steps it (the last step shortened to land on the end), a few steps at a time. Its
// run is a function of the settled world alone, so taking its steps in chunks, between other
// directions' chunks, gives bit for bit what one simulate() call gives.
class Pull {
 public:
  Pull(const World& base, int robot, const Vector3& axis, const ValidationRequest& request,
       DirectionResult& result)
      : world_(base.clone()),
        robot_(robot),
        request_(request),
        rest_(request, base.bodies()[0].model->maxRadius),
        held_(heldPose(base, robot)),
        start_(base.time()),
        end_(base.time() + request.seconds),
        result_(result) {
    // simulate() checks a world starting at time 0 for interpenetration; the settle has done
    // that for this one (same bodies, same poses).
    world_.setGravity(request.gravity * axis);
  }

  bool ended() const { return ended_; }
  bool letGo() const { return ended_ && !result_.held; }

  // Statics shows the grasp bears this pull: it ends held once its first staticsProbeSeconds
  // have kept the object within the probe's share of the let-go limits.
  void trustStatics() { statics_ = true; }

  // Takes up to `steps` steps of the pull; true once it has ended: let go, at rest, run to its
  // end, or stopped by a DynamicsError (result().failure).
  bool advance(int steps) {
    const double slipBefore = result_.slip, turnBefore = result_.turn, timeBefore = world_.time();
    try {
      for (int i = 0; i < steps && !ended_; ++i) {
        if (!(world_.time() < end_ - 1e-12)) {
          ended_ = true;
          break;
        }
        const double h = std::min(request_.dt, end_ - world_.time());
        step(world_, h < request_.dt * 1e-6 ? request_.dt : h);
        ended_ = !measure();
      }
      if (!ended_ && !(world_.time() < end_ - 1e-12)) ended_ = true;
      if (ended_)
        result_.held = result_.slip <= request_.maxSlip && result_.turn <= request_.maxTurn;
    } catch (const DynamicsError& error) {
      result_.failure = error.what();
      result_.held = false;
      ended_ = true;
    }
    const double elapsed = world_.time() - timeBefore;
    slipRate_ = elapsed > 0.0 ? (result_.slip - slipBefore) / elapsed : 0.0;
    turnRate_ = elapsed > 0.0 ? (result_.turn - turnBefore) / elapsed : 0.0;
    return ended_;
  }

  // The share of the let-go limits (slip or turn, whichever is nearer) the object would reach
  // within kForesightSeconds at its latest rate: a pull that is losing the object ranks first.
  // The rate decides: a pull held slows to rest, one let go speeds up (0.05 s foresight took 18 %
  // more steps than 0.5 s on one set of objects, as many on another; 0.3 to 1 s about the same).
  double foreseenLetGo() const {
    return std::max((result_.slip + kForesightSeconds * slipRate_) / request_.maxSlip,
                    (result_.turn + kForesightSeconds * turnRate_) / request_.maxTurn);
  }

 private:
  static constexpr double kForesightSeconds = 0.5;

  // After each step: the largest slip and turn so far; false once the pull has ended (let go, or
  // at rest with what is left of the run counted in).
  bool measure() {
    const Transform now = heldPose(world_, robot_);
    result_.slip = std::max(result_.slip, (now.translation() - held_.translation()).norm());
    result_.turn = std::max(result_.turn,
                            Quaternion(now.linear()).angularDistance(Quaternion(held_.linear())));
    result_.seconds = world_.time() - start_;
    // Once it has let go, the rest of the run cannot bring it back within the limits.
    if (result_.slip > request_.maxSlip || result_.turn > request_.maxTurn) return false;
    if (statics_ && result_.seconds >= request_.staticsProbeSeconds - 1e-9) {
      // Within the probe's share of the limits, and not moving fast enough to reach the limits
      // within what is left of the run at its present speed.
      const double share = request_.staticsProbeShare;
      const double left = request_.seconds - result_.seconds;
      const auto& v = world_.bodies()[0].state.v;
      if (result_.slip <= share * request_.maxSlip && result_.turn <= share * request_.maxTurn &&
          result_.slip + v.head<3>().norm() * left <= request_.maxSlip &&
          result_.turn + v.tail<3>().norm() * left <= request_.maxTurn) {
        result_.byStatics = true;
        return false;
      }
      statics_ = false;  // it moved: the simulation decides, as without statics
    }
    if (!request_.stopAtRest || !rest_.atRest(world_, robot_)) return true;
    // At rest: what is left of the run could move it by restSpeed times the time left at most.
    const double left = request_.seconds - result_.seconds;
    result_.slip += request_.restSpeed * left;
    result_.turn += request_.restSpeed / rest_.radius() * left;
    return false;
  }

  World world_;
  int robot_;
  const ValidationRequest& request_;
  RestWatch rest_;
  Transform held_;
  double start_, end_;
  DirectionResult& result_;
  bool ended_ = false;
  bool statics_ = false;
  double slipRate_ = 0.0, turnRate_ = 0.0;  // over the last advance(), per second
};

// How a validation that stops at its first let go shares the steps among the six pulls: each
// takes kProbeSteps, then the one foreseen nearest to letting go takes kChunkSteps at a time.
// Most grasps that fail lose the object within a few hundredths of a second in one direction,
// while a direction held runs at least restSeconds (0.1 s) and often 0.5 s to come to rest:
// tried in turn, the directions held before the one let go took 80 % of the failing grasps'
// simulated time (the dataset issue's 6 objects, 54 grasps that fail). Shared this way, those
// grasps took 1,645 steps instead of 6,183 (and 1,629 instead of 5,252 on 8 other generated
// objects); the grasps held run every step of their six pulls either way.
constexpr int kProbeSteps = 1;
constexpr int kChunkSteps = 2;

// Runs the pulls until one lets go (the rest are left untried) or all have ended.
void runUntilALetGo(std::array<std::optional<Pull>, 6>& pulls) {
  for (int k = 0; k < 6; ++k) {
    if (pulls[k] && pulls[k]->advance(kProbeSteps) && pulls[k]->letGo()) return;
  }
  for (;;) {
    Pull* next = nullptr;
    for (auto& pull : pulls) {
      if (!pull || pull->ended()) continue;
      if (!next || pull->foreseenLetGo() > next->foreseenLetGo()) next = &*pull;
    }
    if (!next) return;
    if (next->advance(kChunkSteps) && next->letGo()) return;
  }
}

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
  // Statics needs the squeeze at rest and its contacts' forces over the last two steps.
  bool squeezed_at_rest = false;
  std::vector<ContactImpulse> before_last_impulses, last_impulses;
  try {
    base.setGravity(Vector3::Zero());
    RestWatch rest(request, base.bodies()[0].model->maxRadius);
    FreeObjectWatch free_object(request, base.bodies()[0].model->maxRadius);
    const auto settled = [&](const World& w, const StepReport&) {
      if (request.statics) {
        before_last_impulses = std::move(last_impulses);
        last_impulses = w.lastImpulses();
      }
      if (w.time() < kMinSettleSeconds) return true;
      const bool squeezed = rest.atRest(w, robot);  // both watches see every step
      const bool missed = free_object.atRest(w, robot);
      squeezed_at_rest = squeezed;
      return !(squeezed || missed);
    };
    const double start = base.time();
    simulate(base, {.seconds = request.settleSeconds, .dt = request.dt, .onStep = settled});
    result.settleSeconds = base.time() - start;
  } catch (const DynamicsError& error) {
    settle_failure = error.what();
  }
  std::optional<HeldContacts> held_contacts;
  if (request.statics && squeezed_at_rest && settle_failure.empty())
    held_contacts = heldContacts(base, 0, before_last_impulses, last_impulses, request.dt);
  std::array<std::optional<Pull>, 6> pulls;
  for (int k = 0; k < 6; ++k) {
    DirectionResult& direction = result.directions[k];
    direction.direction = axes[k];
    if (!settle_failure.empty()) {  // every direction fails as the squeeze did
      if (k > 0 && !request.allDirections)
        direction.tried = false;  // one let go ends the validation
      else
        direction.failure = settle_failure;
      continue;
    }
    pulls[k].emplace(base, robot, axes[k], request, direction);
    if (held_contacts &&
        staticHold(base, 0, *held_contacts,
                   {.acceleration = request.gravity * axes[k], .margins = request.staticsMargins})
            .holds)
      pulls[k]->trustStatics();
  }
  if (request.allDirections) {
    for (auto& pull : pulls)
      if (pull) pull->advance(std::numeric_limits<int>::max());  // to its end
  } else {
    runUntilALetGo(pulls);
  }
  for (int k = 0; k < 6; ++k) {
    DirectionResult& direction = result.directions[k];
    if (pulls[k] && !pulls[k]->ended()) {  // cut short: another direction let go first
      direction = DirectionResult{.direction = axes[k], .tried = false};
      continue;
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
