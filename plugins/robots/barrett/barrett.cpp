// The Barrett hand. In GraspIt! its subclass only adds a hardware interface: what makes it a
// Barrett (the spread DOF and the breakaway flexion DOFs) is in its robot file and the engine
// handles it. The type checks that the file has that structure, so a mistyped model is noticed.

#include <fmt/format.h>

#include "graspkit/base/log.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::DofType;

class Barrett final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& model) const override {
    const auto& dofs = model.dofs;
    const bool shaped = dofs.size() == 4 && dofs[0].type == DofType::Rigid &&
                        dofs[1].type == DofType::Breakaway && dofs[2].type == DofType::Breakaway &&
                        dofs[3].type == DofType::Breakaway;
    if (!shaped) {
      graspkit::warn(graspkit::WarningKind::Robot, graspkit::SourceLocation{model.file.string()},
                     "a Barrett hand has a rigid spread DOF then three breakaway flexion DOFs; "
                     "this file differs, so it behaves as its file says");
    }
  }
};

void registerBarrett(graspkit::Registrar& registrar) {
  registrar.addRobotType("Barrett", [] { return std::make_shared<const Barrett>(); });
}

}  // namespace

GRASPKIT_PLUGIN("barrett", "1.0.0", registerBarrett)
