#pragma once
// A degree of freedom: one actuated input that drives one or more joints through the coupling
// `joint value = ratio * dof value` (the DH variable adds the joint's offset).

#include <vector>

namespace graspkit {

enum class DofType {
  Rigid,      // 'r': every coupled joint moves with the DOF; one stopped joint stops it
  Breakaway,  // 'b': distal joints keep closing after a proximal joint stops
  Compliant,  // 'c': each joint stops independently
};

char dofTypeLetter(DofType type);

struct Dof {
  DofType type = DofType::Rigid;
  double defaultVelocity = 0.0;  // closing direction and speed for autograsp
  double maxEffort = 0.0;        // N*1e6*mm (revolute) or N*1e6 (prismatic)
  double Kp = 0.0;
  double Kd = 0.0;
  double draggerScale = 0.0;
  double defaultValue = 0.0;     // radians (mm for prismatic), clamped into [min, max]
  double breakAwayTorque = 0.0;  // already multiplied by 1000 as GraspIt! does
  // Range: the intersection over coupled joints of [jointMin, jointMax] / ratio.
  double min = 0.0;
  double max = 0.0;
  std::vector<int> joints;  // robot-wide indices of the joints this DOF drives

  double clamp(double value) const { return value < min ? min : (value > max ? max : value); }
};

}  // namespace graspkit
