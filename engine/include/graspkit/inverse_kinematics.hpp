#pragma once
// Inverse kinematics: the DOF values that put the end of one chain at a target pose. Robot types
// with a closed form (Puma560) provide it through their RobotType; every other robot gets the
// iterative solver below, which follows GraspIt!'s generic one.

#include <string>
#include <vector>

#include "graspkit/transform.hpp"

namespace graspkit {

class Robot;

struct IkRequest {
  int chain = 0;            // whose end (its last link's frame) is placed at the target
  int maxIterations = 200;  // the iterative solver's cap (GraspIt!'s)
};

struct IkResult {
  bool success = false;
  std::vector<double> dofValues;  // every DOF of the robot, when success
  std::string failure;            // why not, when !success
  int iterations = 0;             // the iterative solver's count; 0 for a closed form
};

// Dispatches to the robot's type (closed form where it has one), else the iterative solver.
// Throws graspkit::Error for a bad chain index; an unreachable target is a failed result.
IkResult inverseKinematics(const Robot& robot, const Transform& target, const IkRequest& request = {});

// GraspIt!'s generic solver: Newton steps in DOF space from the robot's current values, with the
// error [dp; rotation error] solved by QR least squares.
IkResult iterativeInverseKinematics(const Robot& robot, const Transform& target,
                                    const IkRequest& request = {});

}  // namespace graspkit
