// NASA's Robonaut hand: a generic hand whose palm overlaps the second link of its first chain
// (the thumb), so GraspIt! excludes that pair from collisions.

#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

class Robonaut final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    model.disableCollision(graspkit::LinkRef{}, graspkit::LinkRef{0, 1});
  }
};

void registerRobonaut(graspkit::Registrar& registrar) {
  registrar.addRobotType("Robonaut", [] { return std::make_shared<const Robonaut>(); });
}

}  // namespace

GRASPKIT_PLUGIN("robonaut", "1.0.0", registerRobonaut)
