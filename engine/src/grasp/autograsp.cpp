#include "graspkit/grasp/autograsp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {
namespace {

constexpr double kStepScale = 0.01;      // GraspIt!: a step is velocity * speed * 0.01
constexpr double kContactInstant = 0.1;  // mm: bisection stops once closer than this
constexpr int kMaxBisections = 40;

// The hand's links (base first), in worldBodies() order.
struct HandBodies {
  std::vector<BodyRef> links;
};

HandBodies handBodies(const World& world, int robot) {
  HandBodies hand;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink() && ref.index == robot) hand.links.push_back(ref);
  return hand;
}

// Each (hand link, partner) the collision filter pairs, whose boxes come within `margin` mm, in
// the order GraspIt! walks each link's partners: by link, then by partner, and a pair of two hand
// links from each side. The broad phase keeps this linear in the bodies for a many-link hand.
std::vector<std::pair<BodyRef, BodyRef>> handPairs(const World& world, const HandBodies& hand,
                                                   double margin) {
  const int robot = hand.links.empty() ? -1 : hand.links.front().index;
  auto isHand = [&](const BodyRef& ref) { return ref.isLink() && ref.index == robot; };
  std::vector<std::pair<BodyRef, BodyRef>> pairs;
  for (const BodyPair& pair : nearbyPairs(world, margin, hand.links)) {
    if (isHand(pair.first)) pairs.emplace_back(pair.first, pair.second);
    if (isHand(pair.second)) pairs.emplace_back(pair.second, pair.first);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// The pairs (link, partner) whose surfaces intersect, for each of `links` (hand links): one
// collision report, which places each body once.
std::vector<std::pair<BodyRef, BodyRef>> collidingPairsOf(const World& world,
                                                          std::span<const BodyRef> links) {
  std::vector<std::pair<BodyRef, BodyRef>> colliding;
  if (links.empty()) return colliding;
  auto listed = [&](const BodyRef& ref) {
    return std::find(links.begin(), links.end(), ref) != links.end();
  };
  for (const CollidingPair& pair : collisionReport(world, {links, false})) {
    if (listed(pair.first)) colliding.emplace_back(pair.first, pair.second);
    if (listed(pair.second)) colliding.emplace_back(pair.second, pair.first);
  }
  return colliding;
}

void requireHand(const World& world, int robot) {
  const Robot& r = world.robot(robot);  // throws for a bad index
  if (r.model().chains.empty() || r.dofCount() == 0) {
    throw Error(fmt::format("robot '{}' has no fingers to close: autograsp needs chains and DOFs",
                            r.name()));
  }
}

// The joints of `link`'s chain from the chain's first joint to the link's last joint: what
// stops when the link touches something.
std::vector<int> jointsBehind(const RobotModel& model, const LinkRef& link) {
  std::vector<int> joints;
  if (link.isBase()) return joints;
  const KinematicChain& chain = model.chains[link.chain];
  const int last = chain.links[link.link].lastJoint;
  for (int j = 0; j <= last; ++j) joints.push_back(chain.firstJoint + j);
  return joints;
}

class Closing {
 public:
  Closing(World& world, int robot, const DofMotion& motion)
      : world_(world),
        robot_(robot),
        hand_(handBodies(world, robot)),
        after_change_(motion.afterDofChange) {
    const RobotModel& model = world.robot(robot).model();
    const auto& values = world.robot(robot).dofValues();
    const int dofs = static_cast<int>(model.dofs.size());
    step_.resize(dofs);
    target_.resize(dofs);
    moving_.assign(dofs, false);
    joint_stopped_.assign(model.jointCount(), false);
    for (int d = 0; d < dofs; ++d) {
      const Dof& dof = model.dofs[d];
      target_[d] = std::clamp(motion.targets[d], dof.min, dof.max);
      const double size = std::abs(motion.steps[d]);
      step_[d] = target_[d] >= values[d] ? size : -size;
      moving_[d] = size != 0.0;
    }
  }

  const HandBodies& hand() const { return hand_; }

  // One step of every moving DOF. Returns false when nothing moves any more.
  bool step(std::vector<double>& from, std::vector<double>& to) {
    refreshMoving();
    const Robot& robot = world_.robot(robot_);
    from.assign(robot.dofValues().begin(), robot.dofValues().end());
    to = from;
    bool any = false;
    for (std::size_t d = 0; d < to.size(); ++d) {
      if (!moving_[d]) continue;
      const double next = from[d] + step_[d];
      to[d] = step_[d] > 0 ? std::min(next, target_[d]) : std::max(next, target_[d]);
      if (std::abs(to[d] - from[d]) < 1e-12) {
        moving_[d] = false;
        to[d] = from[d];
      } else {
        any = true;
      }
    }
    return any;
  }

  void apply(const std::vector<double>& values) {
    world_.setDofValues(robot_, values, LimitPolicy::Clamp);
    if (after_change_) after_change_(world_, robot_);
  }

  // Active pairs (link, partner) whose surfaces intersect, among links that moved.
  std::vector<std::pair<BodyRef, BodyRef>> collisions(const std::vector<bool>& moved) const {
    std::vector<BodyRef> links;
    for (std::size_t i = 0; i < moved.size(); ++i)
      if (moved[i]) links.push_back(hand_.links[i]);
    return collidingPairsOf(world_, links);
  }

  std::vector<bool> movedLinks(const std::vector<Transform>& before) const {
    std::vector<bool> moved(hand_.links.size());
    for (std::size_t i = 0; i < moved.size(); ++i)
      moved[i] = !bodyPose(world_, hand_.links[i]).isApprox(before[i], 1e-14);
    return moved;
  }

  std::vector<Transform> linkPoses() const {
    std::vector<Transform> poses;
    for (const BodyRef& link : hand_.links) poses.push_back(bodyPose(world_, link));
    return poses;
  }

  // Stops the joints behind every link touching something whose next motion the contact blocks.
  void stopBlockedLinks(const std::vector<Contact>& contacts) {
    const Robot& robot = world_.robot(robot_);
    std::vector<double> ahead(robot.dofValues().begin(), robot.dofValues().end());
    for (std::size_t d = 0; d < ahead.size(); ++d)
      if (moving_[d]) ahead[d] += step_[d];
    Robot trial = robot;
    trial.setDofValues(ahead, LimitPolicy::Clamp);
    for (const Contact& contact : contacts) {
      if (!contact.body1.isLink() || contact.body1.index != robot_) continue;
      const Transform now = robot.linkPose(contact.body1.link);
      const Transform next = trial.linkPose(contact.body1.link);
      const Vector3 motion = next * (now.inverse() * contact.position1) - contact.position1;
      // The normal points into the link: moving against it pushes into the other body.
      if (motion.dot(contact.normal) < 0)
        stopJoints(jointsBehind(robot.model(), contact.body1.link));
    }
  }

  // Stops the joints behind each link that touches something, whatever its motion (the contact
  // instant). Returns whether any link does.
  bool stopTouchingLinks() {
    const ContactRequest request;
    std::vector<char> touching(hand_.links.size(), 0);
    bool any = false;
    for (const auto& [link, other] : handPairs(world_, hand_, request.threshold)) {
      const auto at = std::lower_bound(hand_.links.begin(), hand_.links.end(), link);
      char& known = touching[static_cast<std::size_t>(at - hand_.links.begin())];
      if (known || !inContact(world_, link, other, request)) continue;
      known = 1;
      any = true;
      stopJoints(jointsBehind(world_.robot(robot_).model(), link.link));
    }
    return any;
  }

 private:
  void stopJoints(const std::vector<int>& joints) {
    const Robot& robot = world_.robot(robot_);
    const RobotModel& model = robot.model();
    for (int j : joints) {
      if (joint_stopped_[j]) continue;
      joint_stopped_[j] = true;
      const int d = model.joint(j).dof;
      if (model.dofs[d].type == DofType::Rigid) {
        moving_[d] = false;
      } else if (!robot.breakaway()[j].engaged) {
        // The joint holds where it is while the DOF goes on: it breaks away at this value.
        world_.setBreakaway(robot_, j, {true, robot.dofValues()[d]});
      }
    }
  }

  // A DOF stops when every joint it drives is stopped (a rigid one at its first stopped joint).
  void refreshMoving() {
    const RobotModel& model = world_.robot(robot_).model();
    for (std::size_t d = 0; d < moving_.size(); ++d) {
      if (!moving_[d]) continue;
      const auto& joints = model.dofs[d].joints;
      moving_[d] = joints.empty() || !std::all_of(joints.begin(), joints.end(),
                                                  [&](int j) { return joint_stopped_[j]; });
    }
  }

  World& world_;
  int robot_;
  HandBodies hand_;
  std::function<void(World&, int)> after_change_;
  std::vector<double> step_, target_;
  std::vector<bool> moving_;
  std::vector<bool> joint_stopped_;
};

std::vector<double> interpolate(const std::vector<double>& a, const std::vector<double>& b,
                                double t) {
  std::vector<double> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] + t * (b[i] - a[i]);
  return out;
}

// Whether some pair is closer than the contact instant: the bisections' question, answered pair
// by pair so that the first close pair ends it (the same answer as the smallest distance). The
// contact search answers it in a fraction of FCL's time for meshes a hair apart.
bool withinContactInstant(const World& world,
                          const std::vector<std::pair<BodyRef, BodyRef>>& pairs) {
  return std::any_of(pairs.begin(), pairs.end(), [&](const auto& pair) {
    return surfacesWithin(world, pair.first, pair.second, kContactInstant);
  });
}

}  // namespace

std::span<const EnumName<MotionEnd>> enumNames(std::type_identity<MotionEnd>) {
  static constexpr EnumName<MotionEnd> kNames[] = {
      {MotionEnd::Settled, "settled"},
      {MotionEnd::Contact, "contact"},
      {MotionEnd::IterationLimit, "iteration_limit"},
      {MotionEnd::InterpolationError, "interpolation_error"},
      {MotionEnd::NoContact, "no_contact"},
      {MotionEnd::Stopped, "stopped"}};
  return kNames;
}

std::vector<Contact> robotContacts(const World& world, int robot, const BodyRef* object) {
  world.robot(robot);  // range check
  const ContactRequest request;
  std::vector<Contact> contacts;
  for (const auto& [link, other] : handPairs(world, handBodies(world, robot), request.threshold)) {
    if (object && !(other == *object)) continue;
    ContactResult found = findContacts(world, link, other, request);
    contacts.insert(contacts.end(), found.contacts.begin(), found.contacts.end());
  }
  return contacts;
}

std::vector<Contact> contactsWith(const std::vector<Contact>& contacts, const BodyRef& object) {
  std::vector<Contact> with;
  for (const Contact& c : contacts)
    if (c.body2 == object) with.push_back(c);
  return with;
}

AutoGraspResult autoGrasp(World& world, int robot, const AutoGraspOptions& options) {
  const std::shared_ptr<const RobotType>& type = world.robot(robot).model().robotType;
  return type ? type->autoGrasp(world, robot, options) : genericAutoGrasp(world, robot, options);
}

AutoGraspResult genericAutoGrasp(World& world, int robot, const AutoGraspOptions& options) {
  requireHand(world, robot);
  DofMotion motion;
  for (const Dof& dof : world.robot(robot).model().dofs) {
    const double velocity = options.speedFactor * dof.defaultVelocity;
    motion.targets.push_back(velocity >= 0 ? dof.max : dof.min);
    motion.steps.push_back(velocity * kStepScale);
  }
  motion.stopAtContact = options.stopAtContact;
  motion.maxIterations = options.maxIterations;
  motion.keepGoing = options.keepGoing;
  return moveDofsToContacts(world, robot, motion);
}

AutoGraspResult moveDofsToContacts(World& world, int robot, const DofMotion& motion) {
  requireHand(world, robot);
  const std::size_t dofs = world.robot(robot).model().dofs.size();
  if (motion.targets.size() != dofs || motion.steps.size() != dofs) {
    throw Error(fmt::format("robot '{}' has {} DOFs, the motion gives {} targets and {} steps",
                            world.robot(robot).name(), dofs, motion.targets.size(),
                            motion.steps.size()));
  }
  Closing closing(world, robot, motion);
  AutoGraspResult result;
  closing.stopBlockedLinks(robotContacts(world, robot));

  std::vector<double> from, to;
  for (;;) {
    if (result.iterations >= motion.maxIterations) {
      result.end = MotionEnd::IterationLimit;
      break;
    }
    if (motion.keepGoing && !motion.keepGoing()) {
      result.end = MotionEnd::Stopped;
      break;
    }
    if (!closing.step(from, to)) break;
    ++result.iterations;
    const std::vector<Transform> before = closing.linkPoses();
    closing.apply(to);
    const std::vector<bool> moved = closing.movedLinks(before);
    auto colliding = closing.collisions(moved);
    if (colliding.empty()) continue;

    // Bracket the contact instant: free at lo, colliding at hi.
    double lo = 0.0, hi = 1.0;
    bool found = false;
    for (int k = 0; k < kMaxBisections && !found; ++k) {
      const double mid = 0.5 * (lo + hi);
      closing.apply(interpolate(from, to, mid));
      auto now = closing.collisions(moved);
      if (!now.empty()) {
        hi = mid;
        colliding = std::move(now);
      } else {
        lo = mid;
        found = withinContactInstant(world, colliding);
      }
    }
    if (!found && lo == 0.0) {
      // Every bisection point collided: the step started (free) so close to contact that no
      // fraction of it is free. Then the start itself is the contact instant.
      closing.apply(from);
      found = withinContactInstant(world, colliding);
    }
    if (!found) {
      closing.apply(interpolate(from, to, lo));
      result.end = MotionEnd::InterpolationError;
      break;
    }
    const bool touching = closing.stopTouchingLinks();
    if (motion.stopAtContact && touching) {
      result.end = MotionEnd::Contact;
      break;
    }
  }
  // Every joint stopped is marked broken away as it stops; the ones their DOF stopped with are
  // not (they would hold the finger limp in a simulation, which drives it through them).
  world.releaseBreakawayNotLagging(robot);
  const Robot& hand = world.robot(robot);
  result.dofValues.assign(hand.dofValues().begin(), hand.dofValues().end());
  result.contacts = robotContacts(world, robot);
  return result;
}

bool openUntilFree(World& world, int robot) {
  requireHand(world, robot);
  const HandBodies hand = handBodies(world, robot);
  auto free = [&] { return !anyCollision(world, hand.links); };
  const RobotModel& model = world.robot(robot).model();
  // GraspIt!'s quickOpen: chunks of ten autograsp steps against the closing direction.
  for (int chunk = 0; chunk < 1000; ++chunk) {
    if (free()) return true;
    const Robot& r = world.robot(robot);
    std::vector<double> values(r.dofValues().begin(), r.dofValues().end());
    bool moved = false;
    for (std::size_t d = 0; d < values.size(); ++d) {
      const Dof& dof = model.dofs[d];
      const double open = -dof.defaultVelocity * kStepScale * 10.0;
      const double next = std::clamp(values[d] + open, dof.min, dof.max);
      moved = moved || next != values[d];
      values[d] = next;
    }
    if (!moved) break;
    for (std::size_t j = 0; j < r.breakaway().size(); ++j)
      world.setBreakaway(robot, static_cast<int>(j), {});
    world.setDofValues(robot, values);
  }
  return free();
}

AutoGraspResult approachToContact(World& world, int robot, const ApproachOptions& options) {
  world.robot(robot);  // range check
  const HandBodies hand = handBodies(world, robot);
  auto colliding = [&] { return collidingPairsOf(world, hand.links); };
  if (!colliding().empty()) {
    throw Error(fmt::format("robot '{}' collides before it approaches", world.robot(robot).name()));
  }
  const Transform start = world.robot(robot).pose();
  Vector3 direction = start.linear() * world.robot(robot).model().approachFrame().linear().col(2);
  if (options.direction) {
    const double length = options.direction->norm();
    if (!std::isfinite(length) || length < 1e-12)
      throw Error("approach direction must be a finite, non-zero vector");
    direction = *options.direction / length;
  }
  auto placeAt = [&](double s) {
    Transform pose = start;
    pose.translation() += s * direction;
    world.setRobotPose(robot, pose);
  };
  AutoGraspResult result;
  result.end = MotionEnd::NoContact;
  for (double s = 0.0; s < options.maxDistance;) {
    const double next = std::min(s + options.step, options.maxDistance);
    placeAt(next);
    ++result.iterations;
    auto pairs = colliding();
    if (pairs.empty()) {
      s = next;
      continue;
    }
    double lo = s, hi = next;
    result.end = MotionEnd::InterpolationError;
    for (int k = 0; k < kMaxBisections; ++k) {
      const double mid = 0.5 * (lo + hi);
      placeAt(mid);
      auto now = colliding();
      if (!now.empty()) {
        hi = mid;
        pairs = std::move(now);
      } else {
        lo = mid;
        if (withinContactInstant(world, pairs)) {
          result.end = MotionEnd::Contact;
          break;
        }
      }
    }
    placeAt(lo);
    break;
  }
  const Robot& r = world.robot(robot);
  result.dofValues.assign(r.dofValues().begin(), r.dofValues().end());
  result.contacts = robotContacts(world, robot);
  return result;
}

}  // namespace graspkit
