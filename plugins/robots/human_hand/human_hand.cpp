// Tendon-driven hands: GraspIt!'s HumanHand and McGrip.
//
// HumanHand is a hand whose file also lists tendons (routes of insertion points on links) and
// tendon wrappers (cylinders on links the tendons wrap around). The engine reads them into
// RobotModel::tendons and tendonWrappers and provides their geometry and statics
// (graspkit/model/tendon.hpp: tendonPath, tendonLength, tendonRestLength, tendonForce,
// insertionForces, tendonJointTorques), so this type only checks that the tendons are usable.
// Its collision rules are the file's: GraspIt!'s HumanHand adds no exclusion of its own.
//
// McGrip is a HumanHand whose tendons are plain cables, not muscles: they carry only the active
// force, never the passive spring force of a stretched tendon, so configure() switches that off.
// GraspIt!'s McGrip also fixes two construction parameters (kLinkLength, kJointRadius below),
// which only its tendon-routing optimisation (McGripGrasp) uses; that optimisation is not
// reproduced here.

#include <fmt/format.h>

#include <set>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::Error;
using graspkit::LinkRef;
using graspkit::RobotModel;
using graspkit::SourceLocation;

// McGrip's construction parameters in GraspIt! (mm): the length of a finger link and the radius
// of a joint, as its routing matrices assume.
[[maybe_unused]] constexpr double kLinkLength = 20.0;
[[maybe_unused]] constexpr double kJointRadius = 5.0;

SourceLocation in(const RobotModel& model) {
  return SourceLocation{model.file.string()};
}

std::string describe(const LinkRef& link) {
  return link.isBase() ? "the palm" : fmt::format("chain {} link {}", link.chain, link.link);
}

void checkTendons(const RobotModel& model) {
  for (std::size_t t = 0; t < model.tendons.size(); ++t) {
    const graspkit::Tendon& tendon = model.tendons[t];
    // Wrappers exempt tendons by name, so a tendon needs one.
    if (tendon.name.empty())
      throw Error(in(model), fmt::format("<tendon> {} has no name attribute", t));
    if (tendon.insertionPoints.size() < 2)
      throw Error(in(model), fmt::format("tendon '{}' has {} <insertionPoint>s; it needs at "
                                         "least two",
                                         tendon.name, tendon.insertionPoints.size()));
    for (std::size_t p = 0; p < tendon.insertionPoints.size(); ++p) {
      const LinkRef& link = tendon.insertionPoints[p].link;
      if (!model.hasLink(link))
        throw Error(in(model), fmt::format("insertion point {} of tendon '{}' is on {}, which "
                                           "the robot does not have",
                                           p, tendon.name, describe(link)));
    }
  }
}

void checkWrappers(const RobotModel& model) {
  std::set<std::string> names;
  for (const graspkit::Tendon& tendon : model.tendons) names.insert(tendon.name);
  for (std::size_t w = 0; w < model.tendonWrappers.size(); ++w) {
    const graspkit::TendonWrapper& wrapper = model.tendonWrappers[w];
    if (!model.hasLink(wrapper.link))
      throw Error(in(model), fmt::format("<tendonWrapper> {} is on {}, which the robot does "
                                         "not have",
                                         w, describe(wrapper.link)));
    if (!(wrapper.radius > 0.0))
      throw Error(in(model), fmt::format("<tendonWrapper> {} has radius {}; it must be positive", w,
                                         wrapper.radius));
    if (!(wrapper.orientation.norm() > 0.0) || !wrapper.orientation.allFinite())
      throw Error(in(model), fmt::format("<tendonWrapper> {} has no axis direction "
                                         "(<orientation> is zero)",
                                         w));
    // A misspelt exemption silently makes a tendon wrap; say so, but load as GraspIt! does.
    for (const std::string& exempt : wrapper.exemptions)
      if (!names.count(exempt))
        graspkit::warn(graspkit::WarningKind::Robot, in(model),
                       fmt::format("<tendonWrapper> {} exempts tendon '{}', which "
                                   "the robot does not have",
                                   w, exempt));
  }
}

class HumanHand : public graspkit::RobotType {
 public:
  void configure(RobotModel& model) const override {
    checkTendons(model);
    checkWrappers(model);
  }
};

class McGrip final : public HumanHand {
 public:
  void configure(RobotModel& model) const override {
    HumanHand::configure(model);
    for (graspkit::Tendon& tendon : model.tendons) tendon.passiveForce = false;
  }
};

void registerTendonHands(graspkit::Registrar& registrar) {
  registrar.addRobotType("HumanHand", [] { return std::make_shared<const HumanHand>(); });
  registrar.addRobotType("McGrip", [] { return std::make_shared<const McGrip>(); });
}

}  // namespace

GRASPKIT_PLUGIN("human_hand", "1.0.0", registerTendonHands)
