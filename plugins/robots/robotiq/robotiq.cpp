// Robotiq's three-finger adaptive gripper (GraspIt!'s RobotIQ type).
//
// Collisions: the palm overlaps each finger's second link at rest, so that pair is excluded on
// chains 0-2 (on top of the engine's palm / first-link rule).
//
// Autograsp: the real gripper is underactuated, each finger wrapping round the object one
// phalanx after the other. GraspIt! imitates it with a hard-coded closing for exactly 11 DOFs:
//   finger 0 = chain 0, DOFs 0..2, proximal phalanx = link 0;
//   finger 1 = chain 1, DOFs 4..6, proximal phalanx = link 1 (link 0 is the scissor base);
//   finger 2 = chain 2, DOFs 8..10, proximal phalanx = link 1;
//   DOFs 3 and 7 (the scissor, i.e. the grasp mode) never move.
// Rounds of one static motion each (moveDofsToContacts, stopping at the first contact), with
// every DOF stepping by speedFactor * 0.01 rad. After each round, per finger:
//   phase 1: the proximal DOF closes to its max while the middle and distal DOFs go to their
//            min (straightening the finger);
//   phase 2: once the proximal or middle phalanx touches, or the proximal DOF is at its max,
//            the proximal DOF holds and the middle DOF closes to its max;
//   phase 3: once the middle phalanx touches or its DOF is at its max, the middle DOF holds
//            and the distal DOF closes to its max (until its phalanx touches or the limit).
// It ends after a round in which nothing moved, or after a guard of 1000 rounds.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::AutoGraspOptions;
using graspkit::AutoGraspResult;
using graspkit::LinkRef;
using graspkit::World;

constexpr int kDofCount = 11;
constexpr double kStepScale = 0.01;  // rad per step and unit speed, GraspIt!'s autograsp step
constexpr int kMaxRounds = 1000;     // GraspIt!'s guard against a closing that never ends
constexpr double kAtLimit = 1e-12;   // rad: GraspIt! compares with ==; steps land exactly

struct Finger {
  int chain;
  int firstDof;      // proximal DOF; middle and distal follow
  int proximalLink;  // middle and distal links follow
};
constexpr Finger kFingers[] = {{0, 0, 0}, {1, 4, 1}, {2, 8, 1}};

void requireLayout(const graspkit::RobotModel& model) {
  bool ok = model.dofs.size() == kDofCount && model.chains.size() >= 3;
  for (const Finger& f : kFingers) ok = ok && model.hasLink(LinkRef{f.chain, f.proximalLink + 2});
  if (!ok) {
    throw graspkit::Error(fmt::format(
        "{}: the RobotIQ autograsp needs 11 DOFs and chains 0-2 with three phalanges after the "
        "scissor links (chain 0 from link 0, chains 1 and 2 from link 1); robot '{}' has {} DOFs "
        "and {} chains",
        model.file.string(), model.name, model.dofs.size(), model.chains.size()));
  }
}

// The links of robot `robot` that touch something in `contacts`.
std::vector<LinkRef> touchingLinks(const std::vector<graspkit::Contact>& contacts, int robot) {
  std::vector<LinkRef> links;
  for (const graspkit::Contact& c : contacts) {
    if (c.body1.isLink() && c.body1.index == robot) links.push_back(c.body1.link);
    if (c.body2.isLink() && c.body2.index == robot) links.push_back(c.body2.link);
  }
  return links;
}

class RobotIQ final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    for (int chain = 0; chain < 3; ++chain) model.disableCollision(LinkRef{}, LinkRef{chain, 1});
  }

  // Phalanx by phalanx, some DOFs first toward their minimum: within the limits, not one way.
  graspkit::CloseMotion closeMotion() const override {
    return graspkit::CloseMotion::WithinDofLimits;
  }

  AutoGraspResult autoGrasp(World& world, int robot,
                            const AutoGraspOptions& options) const override {
    const graspkit::RobotModel& model = world.robot(robot).model();
    requireLayout(model);
    if (options.speedFactor < 0) return forceOpen(world, robot);

    const double step = std::abs(options.speedFactor) * kStepScale;
    graspkit::DofMotion motion;
    motion.stopAtContact = true;
    motion.keepGoing = options.keepGoing;
    motion.targets.assign(kDofCount, 0.0);
    motion.steps.assign(kDofCount, 0.0);  // DOFs 3 and 7 hold
    for (const Finger& f : kFingers) {
      target(motion, f.firstDof, model.dofs[f.firstDof].max, step);
      target(motion, f.firstDof + 1, model.dofs[f.firstDof + 1].min, step);
      target(motion, f.firstDof + 2, model.dofs[f.firstDof + 2].min, step);
    }

    AutoGraspResult total;
    for (int round = 1;; ++round) {
      const AutoGraspResult r = graspkit::moveDofsToContacts(world, robot, motion);
      total.iterations += r.iterations;
      if (r.end == graspkit::MotionEnd::InterpolationError || r.end == graspkit::MotionEnd::Stopped)
        total.end = r.end;
      const std::vector<LinkRef> touching = touchingLinks(r.contacts, robot);
      const auto values = world.robot(robot).dofValues();
      auto touches = [&](const Finger& f, int phalanx) {
        const LinkRef link{f.chain, f.proximalLink + phalanx};
        return std::find(touching.begin(), touching.end(), link) != touching.end();
      };
      auto atMax = [&](int dof) { return values[dof] >= model.dofs[dof].max - kAtLimit; };
      for (const Finger& f : kFingers) {
        if (!(touches(f, 0) || touches(f, 1) || atMax(f.firstDof))) continue;
        hold(motion, f.firstDof, values);
        target(motion, f.firstDof + 1, model.dofs[f.firstDof + 1].max, step);
        if (!(touches(f, 1) || atMax(f.firstDof + 1))) continue;
        hold(motion, f.firstDof + 1, values);
        target(motion, f.firstDof + 2, model.dofs[f.firstDof + 2].max, step);
      }
      if (r.iterations == 0 || r.end == graspkit::MotionEnd::InterpolationError ||
          r.end == graspkit::MotionEnd::Stopped)
        break;
      if (round > kMaxRounds) {
        total.end = graspkit::MotionEnd::IterationLimit;
        break;
      }
    }
    const auto values = world.robot(robot).dofValues();
    total.dofValues.assign(values.begin(), values.end());
    total.contacts = graspkit::robotContacts(world, robot);
    return total;
  }

 private:
  static void target(graspkit::DofMotion& motion, int dof, double value, double step) {
    motion.targets[dof] = value;
    motion.steps[dof] = step;
  }
  static void hold(graspkit::DofMotion& motion, int dof, std::span<const double> values) {
    motion.targets[dof] = values[dof];
    motion.steps[dof] = 0.0;
  }

  // GraspIt! has no opening for this hand: it jumps to the open pose (every DOF 0, the scissor
  // DOFs kept), without looking for collisions.
  static AutoGraspResult forceOpen(World& world, int robot) {
    const auto now = world.robot(robot).dofValues();
    std::vector<double> open(kDofCount, 0.0);
    open[3] = now[3];
    open[7] = now[7];
    world.setDofValues(robot, open, graspkit::LimitPolicy::Clamp);
    AutoGraspResult result;
    const auto values = world.robot(robot).dofValues();
    result.dofValues.assign(values.begin(), values.end());
    result.contacts = graspkit::robotContacts(world, robot);
    return result;
  }
};

void registerRobotIQ(graspkit::Registrar& registrar) {
  registrar.addRobotType("RobotIQ", [] { return std::make_shared<const RobotIQ>(); });
}

}  // namespace

GRASPKIT_PLUGIN("robotiq", "1.0.0", registerRobotIQ)
