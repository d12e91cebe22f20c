#pragma once
// Tendons and tendon wrappers of tendon-driven hands (HumanHand, McGrip), kept as the robot file
// gives them; statics that use them come with the hand plugins.

#include <string>
#include <vector>

#include "graspkit/link.hpp"

namespace graspkit {

struct TendonInsertionPoint {
  LinkRef link;
  Vector3 position = Vector3::Zero();  // mm, link frame
  double friction = 0.0;
};

struct Tendon {
  std::string name;
  double stiffness = 0.0;  // already multiplied by 1e6
  double restLength = 0.0;
  double preTensionLength = 0.0;
  std::vector<TendonInsertionPoint> insertionPoints;
};

struct TendonWrapper {
  LinkRef link;
  double friction = 0.0;
  Vector3 position = Vector3::Zero();
  Vector3 orientation = Vector3::UnitZ();
  double radius = 0.0;
  double length = 0.0;
  std::vector<std::string> exemptions;                         // tendon names
  std::vector<std::pair<std::string, Vector3>> wrappingSides;  // tendon name, side direction
};

}  // namespace graspkit
