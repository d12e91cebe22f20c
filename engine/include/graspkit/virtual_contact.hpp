#pragma once
// Virtual contacts: points on the hand's surface that the planner's energies use as if they
// touched the object.

#include <vector>

#include "graspkit/transform.hpp"

namespace graspkit {

struct VirtualContact {
  int finger = -1;  // chain index, -1 for the palm
  int link = 0;
  std::vector<Eigen::Matrix<double, 6, 1>> frictionEdges;
  Vector3 location = Vector3::Zero();            // mm, link frame
  Quaternion rotation = Quaternion::Identity();  // contact frame in link frame
  Vector3 translation = Vector3::Zero();
  Vector3 normal = Vector3::UnitZ();
  double sCof = 0.0;
};

}  // namespace graspkit
