#pragma once
// Inverse kinematics: the DOF values that put the end of one chain at a target pose. Robot types
// with a closed form (Puma560) provide it through their RobotType; every other robot gets the
// iterative solver below, which follows GraspIt!'s generic one.

#include <string>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit {

class Robot;

struct IkRequest {
  // Whose end is placed at the target: the world frame of the chain's last link (robot pose *
  // chain base * DH transforms up to that link's last joint), i.e. Robot::chainEndPose(chain).
  int chain = 0;
  int maxIterations = 200;  // the iterative solver's cap on steps (GraspIt!'s)
  // The iterative solver's acceptance of its fixed point (a graspkit addition: GraspIt! accepts
  // any fixed point, even the least-squares nearest pose of an unreachable target). Distance of
  // the end's origin from the target's (mm) and the norm of the rotation error (rad).
  double positionTolerance = 1e-3;
  double orientationTolerance = 1e-5;
};

struct IkResult {
  bool success = false;
  std::vector<double> dofValues;  // every DOF of the robot, when success
  std::string failure;            // why not, when !success
  int iterations = 0;             // the iterative solver's count; 0 for a closed form
};

// inverseKinematics (grasp/robot_type.hpp) picks a robot type's closed form where it has one,
// else this solver.
//
// GraspIt!'s generic solver: Newton steps in DOF space from the robot's current values, with the
// error [dp; rotation error] solved by QR least squares. Only the DOFs that drive the chain's
// joints move. Fails (never throws, except for a bad chain index) when it does not converge,
// when a DOF would move more than 0.2 rad from its current value, when a joint would leave its
// limits, or when its fixed point misses the target by more than the request's tolerances.
IkResult iterativeInverseKinematics(const Robot& robot, const Transform& target,
                                    const IkRequest& request = {});

}  // namespace graspkit
