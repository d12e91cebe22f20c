#pragma once
// A joint of a kinematic chain, described by standard Denavit-Hartenberg parameters, one of
// which (theta for revolute, d for prismatic) is driven by a DOF.

#include "graspkit/math/transform.hpp"

namespace graspkit {

enum class JointType { Revolute, Prismatic };

struct Joint {
  JointType type = JointType::Revolute;
  // Constant DH parameters (mm, rad). The driven one holds the offset c of `d#*k+c`.
  double theta = 0.0;
  double d = 0.0;
  double a = 0.0;
  double alpha = 0.0;
  int dof = 0;         // index of the driving DOF
  double ratio = 1.0;  // joint value = ratio * DOF value
  // Joint limits on the joint value (rad for revolute, mm for prismatic), offset excluded.
  double min = 0.0;
  double max = 0.0;
  // Passive dynamics: torque = -viscous*v - coulomb*sign(v) - spring*(q - rest).
  double viscousFriction = 0.0;
  double coulombFriction = 0.0;
  double springStiffness = 0.0;  // already multiplied by 1e6 as GraspIt! does
  double restValue = 0.0;

  // The joint's DH transform for a joint value (offset excluded).
  Transform transform(double value) const {
    return type == JointType::Revolute ? denavitHartenberg(theta + value, d, a, alpha)
                                       : denavitHartenberg(theta, d + value, a, alpha);
  }
  double offset() const { return type == JointType::Revolute ? theta : d; }
};

}  // namespace graspkit
