#include "graspkit/inverse_kinematics.hpp"

#include <fmt/format.h>

#include "graspkit/error.hpp"
#include "graspkit/robot.hpp"
#include "graspkit/robot_type.hpp"

namespace graspkit {

IkResult inverseKinematics(const Robot& robot, const Transform& target, const IkRequest& request) {
  if (request.chain < 0 || request.chain >= static_cast<int>(robot.model().chains.size()))
    throw Error(fmt::format("robot '{}': inverse kinematics of chain {}, robot has {} chains",
                            robot.name(), request.chain, robot.model().chains.size()));
  const std::shared_ptr<const RobotType>& type = robot.model().robotType;
  return type ? type->inverseKinematics(robot, target, request)
              : iterativeInverseKinematics(robot, target, request);
}

IkResult iterativeInverseKinematics(const Robot& robot, const Transform& target,
                                    const IkRequest& request) {
  (void)robot;
  (void)target;
  (void)request;
  IkResult result;
  result.failure = "iterative inverse kinematics is not built yet";
  return result;
}

}  // namespace graspkit
