#pragma once
// The list planner's input file: a JSON array of hand states, each the hand's world pose (its
// palm frame) and its DOF values,
//
//   [{"translation": [x, y, z], "quaternion": [w, x, y, z], "dofs": [d0, d1, ...]}, ...]
//
// in mm and radians (or mm for prismatic DOFs). An object with a "grasps" array (what
// `graspkit plan --json` prints) is read the same way, so one planner's results can be
// re-ranked with another energy. Other keys of an entry are ignored; the quaternion is
// normalised.

#include <filesystem>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::list {

struct HandState {
  Transform pose = Transform::Identity();
  std::vector<double> dofs;
};

// Throws graspkit::Error naming the file (and the entry, counted from 0) when the file cannot
// be read, is not JSON, or an entry lacks a field or has a malformed one.
std::vector<HandState> readHandStates(const std::filesystem::path& file);

}  // namespace graspkit::list
