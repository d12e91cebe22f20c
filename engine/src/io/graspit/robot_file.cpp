#include "graspkit/io/graspit/robot_file.hpp"

#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "graspkit/model/closing_direction.hpp"
#include "graspkit/model/virtual_contact.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/eigengrasp_file.hpp"
#include "graspkit/io/graspit/virtual_contact_file.hpp"
#include "graspkit/math/units.hpp"
#include "graspkit/plugin/registry.hpp"
#include "io/common/xml.hpp"
#include "model/dof_ranges.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

// The coupling of one joint to its DOF: joint value = ratio * dof value, DH variable = joint
// value + offset.
struct Coupling {
  int dof = 0;
  double ratio = 1.0;
  double offset = 0.0;  // in file units (degrees or mm)
};

// Parses `d#*k+c`: a 'd', the DOF index, an optional '*' and ratio, an optional '+' and offset
// (write a negative offset as '+-5'). GraspIt! checks index > numDOF, an off-by-one; we reject
// every index outside [0, numDOF).
Coupling parseCoupling(const fs::path& file, const XMLElement& element, int dof_count) {
  const std::string expression = xml::text(element);
  auto fail = [&](const std::string& why) {
    return Error(
        xml::at(file, element),
        fmt::format("expression '{}' {}; expected d#*k+c (e.g. d1*0.5+40)", expression, why));
  };
  std::string_view rest(expression);
  if (rest.empty() || rest.front() != 'd') throw fail("does not start with 'd'");
  rest.remove_prefix(1);
  Coupling coupling;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), coupling.dof);
  if (ec != std::errc() || end == rest.data()) throw fail("has no DOF index");
  rest.remove_prefix(end - rest.data());
  if (!rest.empty() && rest.front() == '*') {
    rest.remove_prefix(1);
    const auto stop = std::min(rest.find_first_not_of("0123456789.-"), rest.size());
    auto ratio = xml::toDouble(rest.substr(0, stop));
    if (!ratio || *ratio == 0.0) throw fail("has a bad ratio");
    coupling.ratio = *ratio;
    rest.remove_prefix(stop);
  }
  if (!rest.empty() && rest.front() == '+') {
    rest.remove_prefix(1);
    auto offset = xml::toDouble(rest);
    if (!offset) throw fail("has a bad offset");
    coupling.offset = *offset;
    rest = {};
  }
  if (!rest.empty()) {
    // GraspIt! stops reading here and ignores the rest (BarrettBH8_280 has 'd1-2.46').
    warn(WarningKind::Robot, xml::at(file, element),
         fmt::format("expression '{}': trailing '{}' ignored as GraspIt! does; write a negative "
                     "offset as '+-2.46'",
                     expression, rest));
  }
  if (coupling.dof < 0 || coupling.dof >= dof_count) {
    throw Error(xml::at(file, element), fmt::format("expression '{}' names dof {}, robot has {}",
                                                    expression, coupling.dof, dof_count));
  }
  return coupling;
}

Dof readDof(const fs::path& file, const XMLElement& element) {
  xml::warnUnknownChildren(file, element,
                           {"defaultVelocity", "maxEffort", "Kp", "Kd", "draggerScale",
                            "defaultValue", "breakAwayTorque"});
  Dof dof;
  const char* type = element.Attribute("type");
  const std::string_view t = type ? type : "";
  if (t == "r") {
    dof.type = DofType::Rigid;
  } else if (t == "b") {
    dof.type = DofType::Breakaway;
  } else if (t == "c") {
    dof.type = DofType::Compliant;
  } else {
    throw Error(xml::at(file, element), fmt::format("dof type '{}' is not r, b or c", t));
  }
  dof.defaultVelocity = xml::requiredNumber(file, element, "defaultVelocity");
  dof.maxEffort = xml::requiredNumber(file, element, "maxEffort");
  dof.Kp = xml::requiredNumber(file, element, "Kp");
  dof.Kd = xml::requiredNumber(file, element, "Kd");
  dof.draggerScale = xml::requiredNumber(file, element, "draggerScale");
  dof.defaultValue = xml::optionalNumber(file, element, "defaultValue", 0.0);  // unit fixed later
  if (dof.type == DofType::Breakaway) {
    const double torque = xml::optionalNumber(file, element, "breakAwayTorque", 0.0);
    dof.breakAwayTorque = torque < 0 ? 0.0 : torque * 1000.0;
  }
  return dof;
}

Joint readJoint(const fs::path& file, const XMLElement& element, int dof_count) {
  xml::warnUnknownChildren(file, element,
                           {"theta", "d", "a", "alpha", "minValue", "maxValue", "viscousFriction",
                            "CoulombFriction", "springStiffness", "restValue"});
  Joint joint;
  const char* type = element.Attribute("type");
  const std::string_view t = type ? type : "";
  if (t == "Revolute") {
    joint.type = JointType::Revolute;
  } else if (t == "Prismatic") {
    joint.type = JointType::Prismatic;
  } else {
    throw Error(xml::at(file, element),
                fmt::format("joint type '{}' is not Revolute or Prismatic", t));
  }
  const bool revolute = joint.type == JointType::Revolute;
  // The driven parameter: theta for revolute joints (degrees), d for prismatic ones (mm).
  const XMLElement& driven = xml::requiredChild(file, element, revolute ? "theta" : "d");
  const Coupling coupling = parseCoupling(file, driven, dof_count);
  joint.dof = coupling.dof;
  joint.ratio = coupling.ratio;
  if (revolute) {
    joint.theta = degreesToRadians(coupling.offset);
    joint.d = xml::requiredNumber(file, element, "d");
  } else {
    joint.theta = degreesToRadians(xml::requiredNumber(file, element, "theta"));
    joint.d = coupling.offset;
  }
  joint.a = xml::requiredNumber(file, element, "a");
  joint.alpha = degreesToRadians(xml::requiredNumber(file, element, "alpha"));
  const double scale = revolute ? units::kDegree : 1.0;
  joint.min = xml::requiredNumber(file, element, "minValue") * scale;
  joint.max = xml::requiredNumber(file, element, "maxValue") * scale;
  if (joint.min > joint.max) {
    // GraspIt! (DOF::updateMinMax) orders a reversed pair; files in its tree rely on it.
    warn(WarningKind::Robot, xml::at(file, element),
         fmt::format("minValue {} is greater than maxValue {}; the limits are swapped, as GraspIt! "
                     "does",
                     xml::requiredNumber(file, element, "minValue"),
                     xml::requiredNumber(file, element, "maxValue")));
    std::swap(joint.min, joint.max);
  }
  joint.viscousFriction = xml::optionalNumber(file, element, "viscousFriction", 0.0);
  joint.coulombFriction = xml::optionalNumber(file, element, "CoulombFriction", 0.0);
  const double stiffness = xml::optionalNumber(file, element, "springStiffness", 0.0);
  if (revolute && stiffness < 0) {
    throw Error(xml::at(file, *xml::child(element, "springStiffness")),
                "spring stiffness of a revolute joint must not be negative");
  }
  joint.springStiffness = stiffness * 1.0e6;
  joint.restValue = xml::optionalNumber(file, element, "restValue", 0.0) * scale;
  return joint;
}

DynamicJointType dynamicJointType(const fs::path& file, const XMLElement& element) {
  const char* raw = element.Attribute("dynamicJointType");
  std::string t = raw ? raw : "";
  t.erase(0, t.find_first_not_of(' '));
  t.erase(t.find_last_not_of(' ') + 1);
  if (t == "Revolute") return DynamicJointType::Revolute;
  if (t == "Prismatic") return DynamicJointType::Prismatic;
  if (t == "Universal") return DynamicJointType::Universal;
  if (t == "Ball") return DynamicJointType::Ball;
  if (t == "Fixed") return DynamicJointType::Fixed;
  throw Error(xml::at(file, element),
              fmt::format("dynamicJointType '{}' is not Revolute, Prismatic, Universal, Ball or "
                          "Fixed",
                          t));
}

void readCollisionRule(const fs::path& file, const XMLElement& element, int chain, Link& link) {
  const char* raw = element.Attribute("collisionRule");
  if (!raw) return;
  const std::string_view rule(raw);
  if (rule == "Off") {
    link.collisionRule = CollisionRule::Off;
    return;
  }
  if (rule != "OverlappingPair") {
    throw Error(xml::at(file, element),
                fmt::format("collisionRule '{}' is not Off or OverlappingPair", rule));
  }
  link.collisionRule = CollisionRule::OverlappingPair;
  const char* target_chain = element.Attribute("targetChain");
  if (target_chain && std::string_view(target_chain) == "base") {
    link.overlapTarget = LinkRef{};
    return;
  }
  const auto target_link = xml::intAttribute(file, element, "targetLink");
  if (!target_link) return;  // GraspIt! then disables nothing
  const int target = target_chain ? *xml::intAttribute(file, element, "targetChain") : chain;
  link.overlapTarget = LinkRef{target, *target_link};
}

class RobotReader {
 public:
  RobotReader(const fs::path& file, const LoadOptions& options, ModelCache* cache)
      : file_(file),
        dir_(file.parent_path()),
        link_dir_(dir_ / "iv"),
        options_(options),
        cache_(cache) {}

  std::shared_ptr<const RobotModel> read() {
    xml::Document doc(file_);
    const XMLElement& root = doc.root();
    if (std::string_view(root.Name()) != "robot") {
      throw Error(xml::at(file_, root), "the root element of a robot file must be <robot>");
    }
    xml::warnUnknownChildren(
        file_, root,
        {"palm", "filter", "dof", "chain", "disableCollision", "approachDirection", "eigenGrasps",
         "virtualContacts", "cyberGlove", "flockOfBirds", "tendon", "tendonWrapper"});
    auto robot = std::make_shared<RobotModel>();
    robot->file = file_;
    robot->name = file_.stem().string();
    readType(root, *robot);
    readPalm(root, *robot);
    for (const XMLElement* e : xml::children(root, "dof")) {
      if (robot->dofs.size() == kMaxRobotDofs)
        throw Error(xml::at(file_, *e),
                    fmt::format("more than {} DOFs in one robot", kMaxRobotDofs));
      robot->dofs.push_back(readDof(file_, *e));
    }
    if (robot->dofs.empty()) throw Error(xml::at(file_, root), "a robot needs at least one <dof>");
    for (const XMLElement* e : xml::children(root, "chain")) readChain(*e, *robot);
    if (robot->chains.empty()) {
      throw Error(xml::at(file_, root), "a robot needs at least one <chain>");
    }
    finishDofs(root, *robot);
    checkLinkReferences(root, *robot);
    readExtras(root, *robot);
    if (robot->robotType) {
      try {
        robot->robotType->configure(*robot);
      } catch (const Error& e) {
        // The type's message, located at <robot> (its own location names this file already).
        throw Error(xml::at(file_, root), e.message());
      } catch (const std::exception& e) {
        throw Error(xml::at(file_, root),
                    fmt::format("robot type '{}' failed to configure the robot: {}", robot->type,
                                e.what()));
      } catch (...) {
        throw Error(xml::at(file_, root),
                    fmt::format("robot type '{}' failed to configure the robot: it threw "
                                "something that is not a std::exception",
                                robot->type));
      }
    }
    return robot;
  }

 private:
  void readType(const XMLElement& root, RobotModel& robot) {
    const char* type = root.Attribute("type");
    if (!type || !*type) throw Error(xml::at(file_, root), "<robot> needs a type attribute");
    robot.type = type;
    robot.dbName = root.Attribute("DBName") ? root.Attribute("DBName") : robot.type;
    robot.isHand = robot.type != "Robot";
    Registry& registry = options_.registry ? *options_.registry : Registry::global();
    try {
      robot.robotType = registry.robotType(robot.type);
      robot.typeProvider = registry.provenance(FactoryKind::RobotType, robot.type)->describe();
    } catch (const Error& e) {
      if (!options_.genericRobotFallback) throw Error(xml::at(file_, root), e.message());
      // Asked for: behave as a generic Hand, and say so.
      warn(WarningKind::Plugin, xml::at(file_, root),
           fmt::format("no plugin provides robot type '{}'; loaded as a generic Hand (plugin "
                       "search path: {})",
                       robot.type, registry.plugins().describeSearchPath()));
      robot.robotType = registry.robotType("Hand");
      robot.typeProvider = "generic fallback";
    }
  }

  std::shared_ptr<const BodyModel> body(const XMLElement& element) {
    const std::string name = xml::text(element);
    if (name.empty()) throw Error(xml::at(file_, element), "empty body file name");
    std::shared_ptr<const BodyModel> model;
    try {
      model = loadBodyFile(link_dir_ / name, cache_);
    } catch (const Error& e) {
      throw Error(xml::at(file_, element), e.what());
    }
    warnIfInertiaFallback(*model, xml::at(file_, element));
    return model;
  }

  void readPalm(const XMLElement& root, RobotModel& robot) {
    const XMLElement& palm = xml::requiredChild(file_, root, "palm");
    robot.palmFile = xml::text(palm);
    robot.palm = body(palm);
    if (const char* sensor = palm.Attribute("sensorType")) robot.palmSensorType = sensor;
    for (const XMLElement* f : xml::children(root, "filter")) {
      robot.palmFilters.push_back(f->Attribute("params") ? f->Attribute("params") : "");
    }
  }

  void readChain(const XMLElement& element, RobotModel& robot) {
    xml::warnUnknownChildren(file_, element, {"transform", "joint", "link", "filter"});
    const int index = static_cast<int>(robot.chains.size());
    KinematicChain chain;
    chain.firstJoint = robot.jointCount();
    if (const auto* t = xml::child(element, "transform")) chain.base = xml::transform(file_, *t);
    const int dof_count = static_cast<int>(robot.dofs.size());
    for (const XMLElement* j : xml::children(element, "joint")) {
      if (chain.firstJoint + static_cast<int>(chain.joints.size()) == kMaxRobotJoints) {
        throw Error(xml::at(file_, *j),
                    fmt::format("more than {} joints in one robot", kMaxRobotJoints));
      }
      chain.joints.push_back(readJoint(file_, *j, dof_count));
    }
    if (chain.joints.empty()) throw Error(xml::at(file_, element), "a chain needs a <joint>");
    int last_joint = -1;
    int links_before = 0;
    for (const KinematicChain& other : robot.chains)
      links_before += static_cast<int>(other.links.size());
    for (const XMLElement* l : xml::children(element, "link")) {
      if (links_before + static_cast<int>(chain.links.size()) == kMaxRobotJoints)
        throw Error(xml::at(file_, *l),
                    fmt::format("more than {} links in one robot", kMaxRobotJoints));
      Link link;
      link.jointType = dynamicJointType(file_, *l);
      last_joint += jointsConsumed(link.jointType);
      link.lastJoint = last_joint;
      if (last_joint >= static_cast<int>(chain.joints.size())) {
        throw Error(xml::at(file_, *l),
                    fmt::format("link {} of chain {} needs joint {}, the chain has {} joints",
                                chain.links.size(), index, last_joint, chain.joints.size()));
      }
      link.file = xml::text(*l);
      link.name = fmt::format("{}_chain{}_link{}", robot.name, index, chain.links.size());
      if (const char* sensor = l->Attribute("sensorType")) link.sensorType = sensor;
      readCollisionRule(file_, *l, index, link);
      link.body = body(*l);
      chain.links.push_back(std::move(link));
    }
    if (chain.links.empty()) throw Error(xml::at(file_, element), "a chain needs a <link>");
    if (last_joint + 1 != static_cast<int>(chain.joints.size())) {
      throw Error(xml::at(file_, element),
                  fmt::format("chain {} has {} joints but its {} links use {} (Revolute and "
                              "Prismatic links take 1, Universal 2, Ball 3, Fixed 0)",
                              index, chain.joints.size(), chain.links.size(), last_joint + 1));
    }
    for (const XMLElement* f : xml::children(element, "filter")) {
      const int link_index = xml::integer(file_, *f);
      if (link_index < 0 || link_index >= static_cast<int>(chain.links.size())) {
        throw Error(xml::at(file_, *f), fmt::format("filter names link {}, chain has {} links",
                                                    link_index, chain.links.size()));
      }
      chain.tactileFilters.emplace_back(link_index,
                                        f->Attribute("params") ? f->Attribute("params") : "");
    }
    robot.chains.push_back(std::move(chain));
  }

  // DOF ranges are the intersection of their joints' limits divided by the coupling ratio;
  // default values (degrees for revolute DOFs) are clamped into that range.
  void finishDofs(const XMLElement& root, RobotModel& robot) {
    const std::vector<bool> revolute = model::gatherDofJoints(robot);
    const auto dof_elements = xml::children(root, "dof");
    for (std::size_t d = 0; d < robot.dofs.size(); ++d) {
      Dof& dof = robot.dofs[d];
      if (dof.joints.empty()) {
        warn(WarningKind::Robot, xml::at(file_, *dof_elements[d]),
             fmt::format("DOF {} drives no joint", d));
        dof.min = dof.max = 0.0;
      } else if (dof.min > dof.max) {
        throw Error(xml::at(file_, *dof_elements[d]),
                    fmt::format("DOF {} has an empty range: its joints' limits do not overlap", d));
      }
      if (revolute[d]) dof.defaultValue = degreesToRadians(dof.defaultValue);
      dof.defaultValue = dof.clamp(dof.defaultValue);
    }
  }

  LinkRef linkRef(const XMLElement& element, const char* chain_name, const char* link_name) {
    auto read = [&](const char* name) -> int {
      if (auto a = xml::intAttribute(file_, element, name)) return *a;
      if (const auto* c = xml::child(element, name)) return xml::integer(file_, *c);
      throw Error(xml::at(file_, element), fmt::format("missing {}", name));
    };
    LinkRef ref{read(chain_name), 0};
    ref.link = ref.chain < 0 ? -1 : read(link_name);
    if (ref.chain < 0) ref.chain = -1;
    return ref;
  }

  void checkRef(const RobotModel& robot, const XMLElement& element, const LinkRef& ref) {
    if (ref.isBase()) return;
    if (ref.chain >= static_cast<int>(robot.chains.size()) || ref.link < 0 ||
        ref.link >= static_cast<int>(robot.chains[ref.chain].links.size())) {
      throw Error(xml::at(file_, element),
                  fmt::format("names chain {} link {}, which the robot does not have", ref.chain,
                              ref.link));
    }
  }

  void checkLinkReferences(const XMLElement& root, RobotModel& robot) {
    const auto chain_elements = xml::children(root, "chain");
    for (std::size_t c = 0; c < robot.chains.size(); ++c) {
      const auto link_elements = xml::children(*chain_elements[c], "link");
      for (std::size_t l = 0; l < robot.chains[c].links.size(); ++l) {
        const auto& target = robot.chains[c].links[l].overlapTarget;
        if (target) checkRef(robot, *link_elements[l], *target);
      }
    }
    for (const XMLElement* e : xml::children(root, "disableCollision")) {
      CollisionPair pair{linkRef(*e, "body1_chain", "body1_link"),
                         linkRef(*e, "body2_chain", "body2_link")};
      checkRef(robot, *e, pair.first);
      checkRef(robot, *e, pair.second);
      robot.disabledCollisions.push_back(pair);
    }
  }

  void readExtras(const XMLElement& root, RobotModel& robot) {
    if (const auto* e = xml::child(root, "approachDirection")) {
      ApproachDirection approach;
      approach.referenceLocation =
          xml::vector3(file_, xml::requiredChild(file_, *e, "referenceLocation"));
      approach.direction = xml::vector3(file_, xml::requiredChild(file_, *e, "direction"));
      if (approach.direction.norm() < 1e-12) {
        throw Error(xml::at(file_, *e), "approach direction has zero length");
      }
      robot.approach = approach;
    }
    const int dofs = static_cast<int>(robot.dofs.size());
    robot.eigengrasps = identityEigengrasps(dofs);
    // A side file that cannot be used costs the robot only what it adds, as in GraspIt!
    // (Robot::loadEigenData and loadContactData warn and go on).
    if (const auto* e = xml::child(root, "eigenGrasps")) {
      robot.eigengraspFile = xml::text(*e);
      try {
        robot.eigengrasps = loadEigengraspFile(dir_ / robot.eigengraspFile, dofs);
      } catch (const Error& bad) {
        warn(WarningKind::Eigengrasp, xml::at(file_, *e),
             fmt::format("{}; identity eigengrasps are used", bad.what()));
      }
    }
    if (const auto* e = xml::child(root, "virtualContacts")) {
      robot.virtualContactFile = xml::text(*e);
      try {
        robot.virtualContacts = loadVirtualContactFile(dir_ / robot.virtualContactFile);
      } catch (const Error& bad) {
        warn(WarningKind::VirtualContact, xml::at(file_, *e),
             fmt::format("{}; the robot has no virtual contacts", bad.what()));
      }
    }
    if (const auto* e = xml::child(root, "cyberGlove")) robot.cyberGloveFile = xml::text(*e);
    if (const auto* e = xml::child(root, "flockOfBirds")) {
      FlockOfBirds birds;
      try {
        birds.number = xml::intAttribute(file_, *e, "number").value_or(0);
      } catch (const Error& bad) {
        warn(WarningKind::Robot, xml::at(file_, *e),
             std::string(bad.message()) + "; sensor number 0 used");
      }
      if (const auto* t = xml::child(*e, "transform")) birds.offset = xml::transform(file_, *t);
      robot.flockOfBirds = birds;
    }
    for (const XMLElement* e : xml::children(root, "tendon"))
      robot.tendons.push_back(tendon(*e, robot));
    for (const XMLElement* e : xml::children(root, "tendonWrapper")) {
      robot.tendonWrappers.push_back(tendonWrapper(*e, robot));
    }
  }

  Tendon tendon(const XMLElement& element, const RobotModel& robot) {
    Tendon t;
    t.name = element.Attribute("name") ? element.Attribute("name") : "";
    t.stiffness = xml::optionalNumber(file_, element, "stiffness", 0.0) * 1.0e6;
    // Absent lengths stay absent: the rest length then comes from the default posture.
    if (xml::child(element, "restLength"))
      t.restLength = xml::requiredNumber(file_, element, "restLength");
    if (xml::child(element, "preTensionLength"))
      t.preTensionLength = xml::requiredNumber(file_, element, "preTensionLength");
    for (const XMLElement* p : xml::children(element, "insertionPoint")) {
      TendonInsertionPoint point;
      point.link = linkRef(*p, "chain", "link");
      checkRef(robot, *p, point.link);
      point.position = xml::vector3(file_, xml::requiredChild(file_, *p, "position"));
      point.friction = xml::optionalNumber(file_, *p, "friction", 0.0);
      t.insertionPoints.push_back(point);
    }
    if (t.insertionPoints.size() < 2) {
      throw Error(xml::at(file_, element), "a tendon needs at least two <insertionPoint>s");
    }
    return t;
  }

  TendonWrapper tendonWrapper(const XMLElement& element, const RobotModel& robot) {
    TendonWrapper w;
    w.link = linkRef(element, "chain", "link");
    checkRef(robot, element, w.link);
    w.friction = xml::optionalNumber(file_, element, "friction", 0.0);
    w.position = xml::vector3(file_, xml::requiredChild(file_, element, "position"));
    w.orientation = xml::vector3(file_, xml::requiredChild(file_, element, "orientation"));
    w.radius = xml::requiredNumber(file_, element, "radius");
    w.length = xml::optionalNumber(file_, element, "length", 10.0);  // GraspIt!'s default
    for (const XMLElement* e : xml::children(element, "exemption")) {
      w.exemptions.push_back(e->Attribute("tendon") ? e->Attribute("tendon") : xml::text(*e));
    }
    for (const XMLElement* e : xml::children(element, "wrapping_side")) {
      const char* name = e->Attribute("tendon");
      w.wrappingSides.emplace_back(
          name ? name : "", xml::vector3(file_, xml::requiredChild(file_, *e, "orientation")));
    }
    return w;
  }

  fs::path file_;
  fs::path dir_;
  fs::path link_dir_;
  const LoadOptions& options_;
  ModelCache* cache_;
};

}  // namespace

namespace {

// LoadOptions::closingDirections on a loaded model (a copy: cached models are shared).
std::shared_ptr<const RobotModel> withClosingOverrides(std::shared_ptr<const RobotModel> model,
                                                       const LoadOptions& options,
                                                       const fs::path& file) {
  if (options.closingDirections.empty()) return model;
  auto changed = std::make_shared<RobotModel>(*model);
  std::vector<int> directions;
  for (const Dof& dof : changed->dofs) directions.push_back(dof.defaultVelocity < 0.0 ? -1 : 1);
  for (const auto& [dof, direction] : options.closingDirections) {
    if (dof < 0 || dof >= static_cast<int>(directions.size()))
      throw Error(SourceLocation{file.string()},
                  fmt::format("a closing direction is given for DOF {}; the robot has {} DOFs", dof,
                              directions.size()));
    directions[static_cast<std::size_t>(dof)] = direction;
  }
  setClosingDirections(*changed, directions);
  // A URDF or MJCF hand's derived fingertip contacts face the way the fingers close.
  if (changed->virtualContactFile.empty() && !changed->virtualContacts.empty())
    changed->virtualContacts = deriveFingertipContacts(Robot(changed));
  return changed;
}

}  // namespace

std::shared_ptr<const RobotModel> loadRobotFile(const fs::path& file, const LoadOptions& options,
                                                ModelCache* cache) {
  if (isUrdfFile(file)) return withClosingOverrides(loadUrdfFile(file, options), options, file);
  if (isMjcfFile(file)) return withClosingOverrides(loadMjcfFile(file, options), options, file);
  // Without a caller's cache, a local one still reads a link file used by several links once.
  ModelCache local;
  ModelCache* used = cache ? cache : &local;
  return withClosingOverrides(
      used->robot(file, [&]() { return RobotReader(file, options, used).read(); }), options, file);
}

}  // namespace graspkit
