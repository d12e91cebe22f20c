#pragma once
// Shared by the plugin corpus: a robot type whose effect a test can see (it excludes the palm
// against chain 0's first link from collisions).

#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/registry.hpp"

namespace corpus {

class PalmIgnoresFirstLink final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    model.disableCollision(graspkit::LinkRef{}, graspkit::LinkRef{0, 0});
  }
};

inline graspkit::RobotTypeFactory palmIgnoresFirstLink() {
  return [] { return std::make_shared<const PalmIgnoresFirstLink>(); };
}

}  // namespace corpus
