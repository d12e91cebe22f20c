// Willow Garage's PR2 gripper, two types of GraspIt!'s:
//
// Pr2Gripper (pr2_gripper.xml, pr2_gripper_2008.xml): a generic hand whose two first links
// overlap at the palm, so GraspIt! excludes the pair chain 0 link 0 / chain 1 link 0.
//
// Pr2Gripper2010 (pr2_gripper_2010.xml): in GraspIt! a Hand of its own, not a Pr2Gripper, so it
// has no extra exclusion. It adds a "compliant close", which we make its autograsp: the real
// gripper sits on an arm that yields, so when one fingertip meets the object first the hand
// slides until the other one meets it too. In statics:
//   1. the hand closes as any hand (genericAutoGrasp);
//   2. if exactly one fingertip (link 1 of chain 0 or 1) touches, that fingertip's collisions
//      are switched off, and the hand closes again while, after every change of the DOFs, the
//      base moves so that this fingertip keeps the world pose it had when the phase began;
//   3. the fingertip's collisions are switched back on.
// With both fingertips or neither touching after step 1, nothing more happens. An opening
// (negative speed), a stopAtContact closing, or a hand colliding before it closes (GraspIt!
// refuses the compliant close then) get the plain closing of step 1 only.

#include <fmt/format.h>

#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::AutoGraspOptions;
using graspkit::AutoGraspResult;
using graspkit::BodyRef;
using graspkit::LinkRef;
using graspkit::Transform;
using graspkit::World;

class Pr2Gripper final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    model.disableCollision(LinkRef{0, 0}, LinkRef{1, 0});
  }
};

bool touches(const std::vector<graspkit::Contact>& contacts, const BodyRef& link) {
  for (const graspkit::Contact& c : contacts)
    if (c.body1 == link || c.body2 == link) return true;
  return false;
}

bool handCollides(const World& world, int robot) {
  std::vector<BodyRef> links;
  for (const BodyRef& ref : graspkit::worldBodies(world))
    if (ref.isLink() && ref.index == robot) links.push_back(ref);
  return !links.empty() && graspkit::anyCollision(world, links);
}

class Pr2Gripper2010 final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    if (!model.hasLink(LinkRef{0, 1}) || !model.hasLink(LinkRef{1, 1})) {
      throw graspkit::Error(fmt::format(
          "{}: a Pr2Gripper2010 needs a fingertip (link 1) on chains 0 and 1 for its compliant "
          "close; robot '{}' has {} chains",
          model.file.string(), model.name, model.chains.size()));
    }
  }

  AutoGraspResult autoGrasp(World& world, int robot,
                            const AutoGraspOptions& options) const override {
    const bool compliant =
        options.speedFactor > 0 && !options.stopAtContact && !handCollides(world, robot);
    AutoGraspResult first = graspkit::genericAutoGrasp(world, robot, options);
    if (!compliant || first.end == graspkit::MotionEnd::Stopped) return first;

    const BodyRef tips[] = {BodyRef::robotLink(robot, {0, 1}), BodyRef::robotLink(robot, {1, 1})};
    const bool touching[] = {touches(first.contacts, tips[0]), touches(first.contacts, tips[1])};
    if (touching[0] == touching[1]) return first;
    const BodyRef tip = touching[0] ? tips[0] : tips[1];

    AutoGraspResult second = closeAround(world, robot, tip, options);
    second.iterations += first.iterations;
    return second;
  }

  // The second close holds a fingertip still and moves the base after it.
  graspkit::CloseMotion closeMotion() const override { return graspkit::CloseMotion::Unknown; }

 private:
  // The second closing: `tip` is held still in the world (the base follows it) and ignored by
  // collision detection, as it already rests on the object.
  static AutoGraspResult closeAround(World& world, int robot, const BodyRef& tip,
                                     const AutoGraspOptions& options) {
    const Transform held = graspkit::bodyPose(world, tip);
    graspkit::DofMotion motion;
    for (const graspkit::Dof& dof : world.robot(robot).model().dofs) {
      const double velocity = options.speedFactor * dof.defaultVelocity;
      motion.targets.push_back(velocity >= 0 ? dof.max : dof.min);
      motion.steps.push_back(velocity * 0.01);  // GraspIt!'s autograsp step
    }
    motion.maxIterations = options.maxIterations;
    motion.keepGoing = options.keepGoing;
    motion.afterDofChange = [&held, &tip](World& w, int r) {
      // base' * tip_in_base = held, with tip_in_base = base^-1 * tip_now.
      const Transform now = graspkit::bodyPose(w, tip);
      w.setRobotPose(r, held * now.inverse() * w.robot(r).pose());
    };

    graspkit::CollisionFilter& filter = world.collisionFilter();
    const bool was_enabled = filter.bodyEnabled(tip);
    filter.setBodyEnabled(tip, false);
    AutoGraspResult result;
    try {
      result = graspkit::moveDofsToContacts(world, robot, motion);
    } catch (...) {
      filter.setBodyEnabled(tip, was_enabled);
      throw;
    }
    filter.setBodyEnabled(tip, was_enabled);
    result.contacts = graspkit::robotContacts(world, robot);
    return result;
  }
};

void registerPr2Grippers(graspkit::Registrar& registrar) {
  registrar.addRobotType("Pr2Gripper", [] { return std::make_shared<const Pr2Gripper>(); });
  registrar.addRobotType("Pr2Gripper2010", [] { return std::make_shared<const Pr2Gripper2010>(); });
}

}  // namespace

GRASPKIT_PLUGIN("pr2_gripper", "1.0.0", registerPr2Grippers)
