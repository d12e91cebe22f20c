// The M7 two-arm robot and its tool. GraspIt! excludes, for M7, the base against every link and
// every pair within a chain (the engine excludes the latter for all robots already); for
// M7Tool, the first links of its two chains.

#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::LinkRef;

class M7 final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    for (int c = 0; c < static_cast<int>(model.chains.size()); ++c)
      for (int l = 0; l < static_cast<int>(model.chains[c].links.size()); ++l)
        model.disableCollision(LinkRef{}, LinkRef{c, l});
  }
};

class M7Tool final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    model.disableCollision(LinkRef{0, 0}, LinkRef{1, 0});
  }
};

void registerM7(graspkit::Registrar& registrar) {
  registrar.addRobotType("M7", [] { return std::make_shared<const M7>(); });
  registrar.addRobotType("M7Tool", [] { return std::make_shared<const M7Tool>(); });
}

}  // namespace

GRASPKIT_PLUGIN("m7", "1.0.0", registerM7)
