#include "graspkit/grasp/robot_type.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"

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

CloseMotion RobotType::closeMotion() const {
  return CloseMotion::TowardClosingEnds;
}

IkResult inverseKinematics(const Robot& robot, const Transform& target, const IkRequest& request) {
  if (request.chain < 0 || request.chain >= static_cast<int>(robot.model().chains.size()))
    throw Error(fmt::format("robot '{}': inverse kinematics of chain {}, robot has {} chains",
                            robot.name(), request.chain, robot.model().chains.size()));
  const std::shared_ptr<const RobotType>& type = robot.model().robotType;
  return type ? type->inverseKinematics(robot, target, request)
              : iterativeInverseKinematics(robot, target, request);
}

}  // namespace graspkit
