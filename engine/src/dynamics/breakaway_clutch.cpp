#include "dynamics/breakaway_clutch.hpp"

#include <map>

#include "graspkit/model/kinematic_chain.hpp"

namespace graspkit::dynamics {

namespace {

// The direction a DOF closes in (as setClosingTargets and the autograsp take it).
double closingSign(const Dof& dof) {
  return dof.defaultVelocity < 0.0 ? -1.0 : 1.0;
}

// Whether joint `local` of `chain` drives through a clutch that can slip: a breakaway DOF's
// joint, not yet slipped, with a joint of the same DOF beyond it for the DOF to go on driving.
bool canSlip(const Robot& robot, const KinematicChain& chain, int local) {
  const Joint& joint = chain.joints[local];
  const Dof& dof = robot.model().dofs[joint.dof];
  if (dof.type != DofType::Breakaway || dof.breakAwayTorque <= 0.0) return false;
  if (robot.breakaway()[chain.firstJoint + local].engaged) return false;
  for (std::size_t beyond = local + 1; beyond < chain.joints.size(); ++beyond) {
    if (chain.joints[beyond].dof == joint.dof &&
        !robot.breakaway()[chain.firstJoint + beyond].engaged)
      return true;
  }
  return false;
}

// Adds to `torques` (robot-wide joint index -> torque) what force F at world point p on link
// `link` of robot `r` exerts about each joint behind it that can slip.
void addTorques(const World& world, int r, const LinkRef& link, const Vector3& p, const Vector3& F,
                std::map<int, double>& torques) {
  if (link.isBase()) return;
  const Robot& robot = world.robot(r);
  const KinematicChain& chain = robot.model().chains[link.chain];
  const int last = chain.links[link.link].lastJoint;
  if (last < 0) return;
  const Transform chain_base = robot.pose() * chain.base;
  const std::vector<Transform> frames = jointFrames(
      chain, chain_base, robot.jointValues().subspan(chain.firstJoint, chain.joints.size()));
  for (int j = 0; j <= last; ++j) {
    if (!canSlip(robot, chain, j)) continue;
    const Transform& before = j == 0 ? chain_base : frames[j - 1];
    const Vector3 axis = before.linear().col(2);
    const double torque = chain.joints[j].type == JointType::Revolute
                              ? axis.dot((p - before.translation()).cross(F))
                              : axis.dot(F);
    torques[chain.firstJoint + j] += torque;
  }
}

}  // namespace

void updateBreakawayClutches(const World& before, World& next,
                             const std::vector<ContactImpulse>& impulses, double h) {
  for (int r = 0; r < next.robotCount(); ++r) {
    const Robot& robot = next.robot(r);
    const RobotModel& model = robot.model();
    // A clutch takes hold again once its DOF is back where the joint broke away.
    for (int j = 0; j < model.jointCount(); ++j) {
      const BreakawayState& state = robot.breakaway()[j];
      if (!state.engaged) continue;
      const Dof& dof = model.dofs[model.joint(j).dof];
      if ((robot.dofValues()[model.joint(j).dof] - state.value) * closingSign(dof) < 0.0)
        next.setBreakaway(r, j, {});
    }
    // The contacts' push on each joint that can slip, over the step.
    std::map<int, double> torques;
    for (const ContactImpulse& contact : impulses) {
      const Vector3 p = bodyPose(before, contact.body1) * contact.localPoint;
      const Vector3 force = contact.impulse / h;  // on body1; body2 gets its opposite
      if (contact.body1.isLink() && contact.body1.index == r)
        addTorques(before, r, contact.body1.link, p, force, torques);
      if (contact.body2.isLink() && contact.body2.index == r)
        addTorques(before, r, contact.body2.link, p, -force, torques);
    }
    for (const auto& [j, torque] : torques) {
      const Joint& joint = model.joint(j);
      const Dof& dof = model.dofs[joint.dof];
      // Slips when the contacts hold the joint back harder than the clutch transmits.
      const double closing = closingSign(dof) * (joint.ratio < 0.0 ? -1.0 : 1.0);
      if (-closing * torque > dof.breakAwayTorque * kNewtonMillimetre)
        next.setBreakaway(r, j, {true, robot.dofValues()[joint.dof]});
    }
  }
}

}  // namespace graspkit::dynamics
