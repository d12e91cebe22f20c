// gripper3: the plugin of graspkit's custom-robot example. It adds two things graspkit does not
// know:
//   robot type "ThreeFingerGripper"  the three-finger centring gripper of
//                                    models/gripper3/gripper3.xml, with a structure check and a
//                                    closed-form inverse kinematics;
//   quality measure "force_closure"  1 when the grasp is force closure, 0 otherwise.
// Built against an installed graspkit (see CMakeLists.txt and README.md).

#include <cmath>
#include <memory>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::Error;
using graspkit::IkRequest;
using graspkit::IkResult;
using graspkit::Robot;
using graspkit::RobotModel;
using graspkit::Transform;

// How far off the finger's line of travel (mm) and off its orientation (rad) a target may be
// and still count as reached.
constexpr double kPositionTolerance = 1e-6;
constexpr double kAngleTolerance = 1e-9;

class ThreeFingerGripper final : public graspkit::RobotType {
 public:
  // The closed-form inverse kinematics relies on this structure, so a model that differs is
  // refused when it is loaded rather than solved wrongly later.
  void configure(RobotModel& model) const override {
    const graspkit::SourceLocation where{model.file.string()};
    if (model.dofs.size() != 1 || model.chains.size() != 3) {
      throw Error(where, "a ThreeFingerGripper has 1 DOF and 3 chains, this model has " +
                             std::to_string(model.dofs.size()) + " and " +
                             std::to_string(model.chains.size()));
    }
    for (const graspkit::KinematicChain& chain : model.chains) {
      if (chain.joints.size() != 1 || chain.joints[0].type != graspkit::JointType::Prismatic ||
          chain.joints[0].ratio == 0.0) {
        throw Error(where, "every ThreeFingerGripper finger is one prismatic joint driven by d0");
      }
    }
  }

  // A finger only slides along its own z axis, so the end of chain c at DOF value v is its pose
  // at v = 0 moved by ratio * v along that axis. A target is reachable when it lies on that line
  // with the finger's orientation; v is then its offset along the axis divided by the ratio.
  IkResult inverseKinematics(const Robot& robot, const Transform& target,
                             const IkRequest& request) const override {
    const RobotModel& model = robot.model();
    if (request.chain < 0 || request.chain >= static_cast<int>(model.chains.size()))
      throw Error("ThreeFingerGripper has no chain " + std::to_string(request.chain));

    Robot open = robot;
    open.setDofValues(std::vector<double>{0.0}, graspkit::LimitPolicy::Ignore);
    const Transform local = open.chainEndPose(request.chain).inverse() * target;

    IkResult result;
    const double sideways = local.translation().head<2>().norm();
    const double turn = Eigen::AngleAxisd(local.linear()).angle();
    if (sideways > kPositionTolerance || turn > kAngleTolerance) {
      result.failure = "the target is off the finger's line of travel";
      return result;
    }
    const graspkit::Joint& joint = model.chains[request.chain].joints[0];
    const double value = local.translation().z() / joint.ratio;
    const graspkit::Dof& dof = model.dofs[0];
    if (value < dof.min || value > dof.max) {
      result.failure =
          "the finger would travel " + std::to_string(value) + " mm, outside its range";
      return result;
    }
    result.success = true;
    result.dofValues = {value};
    return result;
  }
};

class ForceClosure final : public graspkit::QualityMeasure {
 public:
  std::string name() const override { return "force_closure"; }
  double evaluate(const graspkit::GraspWrenchSpace& gws) const override {
    return gws.built && graspkit::isForceClosure(gws) ? 1.0 : 0.0;
  }
};

void registerGripper3(graspkit::Registrar& registrar) {
  registrar.addRobotType("ThreeFingerGripper",
                         [] { return std::make_shared<const ThreeFingerGripper>(); });
  registrar.addQualityMeasure("force_closure", [] { return std::make_unique<ForceClosure>(); });
}

}  // namespace

GRASPKIT_PLUGIN("gripper3", "1.0.0", registerGripper3)
