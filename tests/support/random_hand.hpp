#pragma once
// A random placement of a world's first robot, a Barrett-like hand of 4 DOFs, near a point:
// any orientation, the palm within a 160 mm cube about `center`, each DOF in [0, 2.4] rad. Tests
// use it to meet the object from every side at every posture.

#include <random>
#include <vector>

#include "graspkit/model/world.hpp"

namespace graspkit::test {

inline void placeHandRandomlyNear(World& world, const Vector3& center, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vector3 axis(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
  Transform pose = Transform::Identity();
  pose.linear() = Eigen::AngleAxisd(6.3 * unit(random), axis.normalized()).toRotationMatrix();
  pose.translation() =
      center + 160 * Vector3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
  world.setRobotPose(0, pose);
  std::vector<double> dofs(4);
  for (double& d : dofs) d = 2.4 * unit(random);
  world.setDofValues(0, dofs);
}

}  // namespace graspkit::test
