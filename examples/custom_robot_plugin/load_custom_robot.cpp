// load_custom_robot: a host program using graspkit's C++ API with the gripper3 plugin. It loads
// the example's robot and world files (their type, ThreeFingerGripper, comes from the plugin
// found on GRASPKIT_PLUGIN_PATH), then checks what the plugin does against values worked out
// by hand from the gripper's geometry (models/gripper3/gripper3.xml):
//   - inverse kinematics: the plugin's closed form, checked by forward kinematics (and by the
//     engine's iterative solver when it has one);
//   - autograsp around the can in models/gripper3_can.xml;
//   - the plugin's quality measure "force_closure" on that grasp.
// Prints one line per result and exits 1 when a check fails, 2 on a graspkit::Error.
//
//   load_custom_robot models/gripper3/gripper3.xml models/gripper3_can.xml

#include <cmath>
#include <cstdio>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::FactoryKind;
using graspkit::Registry;

// Fully open, each grasping face is 50 mm from the palm axis and DOF d0 moves it d0 inwards.
constexpr double kOpenRadius = 50.0;
constexpr double kCanRadius = 30.0;  // models/objects/can.xml
constexpr double kIkTravel = 12.5;   // the finger travel the IK target asks for

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::printf("FAILED: %s\n", what.c_str());
    ++failures;
  }
}

std::string provider(FactoryKind kind, const std::string& name) {
  const auto from = Registry::global().provenance(kind, name);
  if (!from) return "nobody";
  return from->describe() + (from->file.empty() ? "" : " (" + from->file.string() + ")");
}

// The type must come from the plugin, not from the engine's generic fallback.
void checkType(const graspkit::RobotModel& model) {
  std::printf("robot %s: type %s from plugin %s\n", model.name.c_str(), model.type.c_str(),
              provider(FactoryKind::RobotType, model.type).c_str());
  const auto from = Registry::global().provenance(FactoryKind::RobotType, model.type);
  check(model.type == "ThreeFingerGripper", "robot type " + model.type);
  check(from && from->plugin == "gripper3", "type provider " + model.typeProvider);
}

// Finger 0 sits at 90 degrees, so its frame at DOF 0 is at (0, 50, 1) and closing moves it
// along palm -y: the target kIkTravel further in must give d0 = kIkTravel, by either solver.
void checkInverseKinematics(const std::shared_ptr<const graspkit::RobotModel>& model) {
  graspkit::Robot robot(model);
  const graspkit::Transform target =
      robot.chainEndPose(0) * Eigen::Translation3d(0.0, 0.0, kIkTravel);
  check(target.translation().isApprox(Eigen::Vector3d(0.0, kOpenRadius - kIkTravel, 1.0), 1e-9),
        "finger 0's closing direction is not palm -y");

  const graspkit::IkResult closed = graspkit::inverseKinematics(robot, target, {.chain = 0});
  check(closed.success, "IK failed: " + closed.failure);
  if (!closed.success) return;
  std::printf("ik: closed form d0 = %.6f mm in %d iterations (expected %.6f)\n",
              closed.dofValues[0], closed.iterations, kIkTravel);
  check(closed.iterations == 0, "the plugin's IK was not used");
  check(std::abs(closed.dofValues[0] - kIkTravel) < 1e-9, "closed-form d0");

  // Forward kinematics puts the finger where the target is.
  graspkit::Robot moved = robot;
  moved.setDofValues(closed.dofValues);
  check(moved.chainEndPose(0).isApprox(target, 1e-9), "the IK solution misses the target");

  // The engine's own solver as a second opinion, where this graspkit has one.
  const graspkit::IkResult iterative =
      graspkit::iterativeInverseKinematics(robot, target, {.chain = 0});
  if (iterative.success) {
    std::printf("ik: engine's iterative solver d0 = %.6f mm in %d iterations\n",
                iterative.dofValues[0], iterative.iterations);
    check(std::abs(iterative.dofValues[0] - kIkTravel) < 1e-3, "iterative d0");
  } else {
    std::printf("ik: engine's iterative solver unavailable: %s\n", iterative.failure.c_str());
  }

  // And the unreachable: a target beside the finger's line of travel.
  const graspkit::IkResult beside = graspkit::inverseKinematics(
      robot, target * Eigen::Translation3d(5.0, 0.0, 0.0), {.chain = 0});
  std::printf("ik: target 5 mm beside the line of travel: %s\n",
              beside.success ? "reached" : beside.failure.c_str());
  check(!beside.success, "a target off the finger's line was reached");
}

// Around the can (centred under the palm) all three faces stop where they meet its side:
// d0 = 50 - 30 = 20 mm, give or take the contact threshold (0.2 mm) and the flats of the
// tessellated cylinder (a 0.2 mm band for Inventor's default complexity).
void checkGrasp(const std::string& world_file) {
  graspkit::World world = graspkit::loadWorldFile(world_file);
  check(world.robotCount() == 1 && world.bodies().size() == 1, "the world's contents");
  if (world.robotCount() != 1 || world.bodies().size() != 1) return;

  const graspkit::AutoGraspResult closed = graspkit::autoGrasp(world, 0);
  const double d0 = closed.dofValues[0];
  std::printf("autograsp: d0 = %.4f mm (expected %.1f +- 0.5), %zu contacts\n", d0,
              kOpenRadius - kCanRadius, closed.contacts.size());
  check(std::abs(d0 - (kOpenRadius - kCanRadius)) < 0.5, "autograsp d0");
  check(closed.contacts.size() >= 3, "every finger touches the can");

  const graspkit::Grasp grasp = graspkit::analyzeGrasp(world, 0, graspkit::BodyRef::body(0));
  const auto measure = Registry::global().makeQualityMeasure("force_closure");
  const double quality = measure->evaluate(grasp.wrenchSpace);
  std::printf("quality force_closure = %g from plugin %s; engine epsilon = %.6f\n", quality,
              provider(FactoryKind::QualityMeasure, "force_closure").c_str(), grasp.epsilon);
  // Three frictional faces 120 degrees apart hold the can against any wrench; the engine's
  // epsilon (positive exactly for force closure) is the second opinion.
  check(quality == 1.0, "force_closure");
  check((quality == 1.0) == (grasp.epsilon > 0.0), "force_closure disagrees with epsilon");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s ROBOT.xml WORLD.xml\n", argv[0]);
    return 2;
  }
  try {
    const auto model = graspkit::loadRobotFile(argv[1]);
    checkType(*model);
    checkInverseKinematics(model);
    checkGrasp(argv[2]);
  } catch (const graspkit::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  std::printf(failures == 0 ? "all checks passed\n" : "%d checks failed\n", failures);
  return failures == 0 ? 0 : 1;
}
