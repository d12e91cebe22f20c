// The Shadow hand: a generic hand with two pairs GraspIt! excludes from collisions because the
// meshes overlap at rest: the palm with chain 4's second link (the thumb), and the first links
// of chains 0 and 1.

#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::LinkRef;

class Shadow final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    model.disableCollision(LinkRef{}, LinkRef{4, 1});
    model.disableCollision(LinkRef{1, 0}, LinkRef{0, 0});
  }
};

void registerShadow(graspkit::Registrar& registrar) {
  registrar.addRobotType("Shadow", [] { return std::make_shared<const Shadow>(); });
}

}  // namespace

GRASPKIT_PLUGIN("shadow", "1.0.0", registerShadow)
