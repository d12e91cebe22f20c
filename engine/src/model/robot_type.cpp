#include "graspkit/robot_type.hpp"

#include "graspkit/registry.hpp"
#include "graspkit/robot.hpp"
#include "graspkit/world.hpp"
#include "plugin/builtins.hpp"

namespace graspkit {

void RobotType::configure(RobotModel& /*model*/) const {}

IkResult RobotType::inverseKinematics(const Robot& robot, const Transform& target,
                                      const IkRequest& request) const {
  return iterativeInverseKinematics(robot, target, request);
}

AutoGraspResult RobotType::autoGrasp(World& world, int robot,
                                     const AutoGraspOptions& options) const {
  return genericAutoGrasp(world, robot, options);
}

void addBuiltinRobotTypes(Registry& registry) {
  // "Robot" (an arm, no hand behaviour) and "Hand" differ only in RobotModel::isHand, which the
  // robot file reader sets from the type name; both behave generically.
  auto generic = [] { return std::make_shared<const RobotType>(); };
  registry.addRobotType("Robot", generic);
  registry.addRobotType("Hand", generic);
}

}  // namespace graspkit
