#pragma once
// One point of a SearchSpace: the variable values (posture first, then position) and, once
// evaluated, its energy (lower is better).

#include <vector>

namespace graspkit {

// GraspIt!'s energy of a state never evaluated.
inline constexpr double kUnevaluatedEnergy = 1.0e8;

struct SearchState {
  std::vector<double> values;
  double energy = kUnevaluatedEnergy;
};

}  // namespace graspkit
