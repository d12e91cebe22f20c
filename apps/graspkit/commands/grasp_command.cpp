// graspkit grasp: place a hand, optionally close it, and report its contacts and grasp quality.

#include <algorithm>
#include <charconv>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "commands/grasp_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "support/argument_checks.hpp"
#include "support/robot_choice.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

BodyRef findObject(const World& world, const std::string& name) {
  const auto& bodies = world.bodies();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (name.empty() ? bodies[i].isDynamic() : bodies[i].name == name) return BodyRef::body(i);
  }
  if (name.empty()) throw Error("the world has no graspable body to grasp");
  std::string known;
  for (const Body& b : bodies) known += (known.empty() ? "" : ", ") + b.name;
  throw Error(fmt::format("--object: no body '{}' in the world (bodies: {})", name, known));
}

Transform parsePose(const std::string& text) {
  const std::vector<double> v = parseNumberList(text, "--pose");
  if (v.size() != 7) {
    throw Error(fmt::format("--pose: expected tx,ty,tz,qw,qx,qy,qz (7 numbers), got {}", v.size()));
  }
  const std::optional<Quaternion> q = unitQuaternion(v[3], v[4], v[5], v[6]);
  if (!q) throw Error("--pose: the quaternion is zero or not finite: it names no rotation");
  if (const char* why = translationProblem(Vector3(v[0], v[1], v[2])))
    throw Error(fmt::format("--pose: the translation {}", why));
  return makeTransform(Vector3(v[0], v[1], v[2]), *q);
}

WrenchSpaceType parseGws(const std::string& text) {
  if (const auto type = valueNamed<WrenchSpaceType>(text)) return *type;
  throw Error(fmt::format("--gws: '{}' is not L1 or Linf", text));
}

json vec(const Vector3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

json contactJson(const World& world, const Contact& c) {
  json j = {{"link", bodyName(world, c.body1)},
            {"body", bodyName(world, c.body2)},
            {"position", vec(c.position1)},
            {"normal", vec(c.normal)},
            {"mu", c.mu},
            {"model", nameOf(c.model)}};
  if (c.model == ContactModel::SoftFinger) {
    j["torsion"] = c.torsion;
    j["relative_radii"] = {c.patchRadius1, c.patchRadius2};
  }
  return j;
}

// The pairs the hand intersects as placed, before any closing. Intersecting surfaces give no
// contacts, so a hand that starts inside the object would otherwise just report none: warn.
json handCollisions(const World& world, int robot) {
  std::vector<BodyRef> hand;
  for (const BodyRef& b : worldBodies(world))
    if (b.isLink() && b.index == robot) hand.push_back(b);
  json pairs = json::array();
  for (const CollidingPair& pair : collisionReport(world, {hand, false})) {
    const bool first_is_hand = pair.first.isLink() && pair.first.index == robot;
    const BodyRef& link = first_is_hand ? pair.first : pair.second;
    const BodyRef& other = first_is_hand ? pair.second : pair.first;
    pairs.push_back({{"link", bodyName(world, link)}, {"body", bodyName(world, other)}});
  }
  if (!pairs.empty()) {
    warn(WarningKind::Collision, SourceLocation{},
         fmt::format(
             "the hand starts in collision ({} with {}{}): intersecting surfaces give no contacts",
             pairs[0]["link"].get<std::string>(), pairs[0]["body"].get<std::string>(),
             pairs.size() > 1 ? fmt::format(", and {} more pairs", pairs.size() - 1) : ""));
  }
  return pairs;
}

// GraspIt!'s grasp counts only the contacts with the object; the hand's others (finger on
// finger, on an obstacle, on another robot) are reported apart, each saying which it is.
json graspJson(const World& world, const Grasp& grasp) {
  json contacts = json::array(), others = json::array();
  for (const Contact& c : grasp.contacts) {
    if (c.body2 == grasp.object) {
      contacts.push_back(contactJson(world, c));
      continue;
    }
    json other = contactJson(world, c);
    const bool self = c.body2.isLink() && c.body2.index == grasp.robot;
    other["kind"] = self ? "self" : c.body2.isLink() ? "robot" : "body";
    others.push_back(std::move(other));
  }
  const auto dofs = world.robot(grasp.robot).dofValues();
  json j = {{"robot", world.robot(grasp.robot).name()},
            {"object", bodyName(world, grasp.object)},
            {"contacts", contacts},
            {"other_contacts", others},
            {"dof_values", std::vector<double>(dofs.begin(), dofs.end())},
            {"epsilon", grasp.epsilon},
            {"volume", grasp.volume},
            {"force_closure", grasp.forceClosure}};
  if (!grasp.wrenchSpace.built) j["wrench_space_failure"] = grasp.wrenchSpace.failure;
  return j;
}

void printContacts(const json& list, std::ostream& out) {
  for (const auto& c : list) {
    const auto& p = c["position"];
    const auto& n = c["normal"];
    out << fmt::format(
        "  {:<24} {:<12} p [{:.4f} {:.4f} {:.4f}]  n [{:.5f} {:.5f} {:.5f}]  mu {}{}\n",
        c["link"].get<std::string>(), c["body"].get<std::string>(), p[0].get<double>(),
        p[1].get<double>(), p[2].get<double>(), n[0].get<double>(), n[1].get<double>(),
        n[2].get<double>(), c["mu"].get<double>(),
        c.contains("torsion") ? fmt::format("  soft, e_tau {:.4f} mm", c["torsion"].get<double>())
                              : "");
  }
}

void printText(const json& j, std::ostream& out) {
  out << fmt::format("hand {}, object {}\n", j["robot"].get<std::string>(),
                     j["object"].get<std::string>());
  out << fmt::format("{} contacts with the object\n", j["contacts"].size());
  printContacts(j["contacts"], out);
  const json& others = j["other_contacts"];
  if (!others.empty()) {
    const auto self = std::count_if(others.begin(), others.end(),
                                    [](const json& c) { return c["kind"] == "self"; });
    out << fmt::format("{} other contacts ({} between the hand's own links)\n", others.size(),
                       self);
    printContacts(others, out);
  }
  if (j.contains("autograsp"))
    out << fmt::format("autograsp ended: {} after {} steps\n",
                       j["autograsp"]["ended"].get<std::string>(),
                       j["autograsp"]["steps"].get<int>());
  if (!j["start_collisions"].empty())
    out << fmt::format("the hand started in collision ({} pairs)\n", j["start_collisions"].size());
  out << "dof values:";
  for (const auto& v : j["dof_values"]) out << fmt::format(" {:.6f}", v.get<double>());
  // The method on a line of its own: scripts and the other front ends read the figures' lines.
  out << fmt::format("\nepsilon {:.7g}\nvolume {:.7g}\nforce closure {}\nepsilon by {}\n",
                     j["epsilon"].get<double>(), j["volume"].get<double>(),
                     j["force_closure"].get<bool>() ? "yes" : "no",
                     j["epsilon_method"].get<std::string>());
  if (j.contains("wrench_space_failure"))
    out << "wrench space: " << j["wrench_space_failure"].get<std::string>() << "\n";
}

}  // namespace

void addGraspCommand(CLI::App& app, GraspOptions& options) {
  CLI::App* cmd =
      app.add_subcommand("grasp", "Place a hand, optionally close it, report contacts and quality");
  cmd->add_option("world", options.world, "World XML")->required()->check(existingFile());
  addLoadFlags(*cmd, options.load);
  cmd->add_option("--robot", options.robot,
                  "The hand: a robot's name or 0-based index (default: the world's first hand)");
  cmd->add_option("--object", options.object, "The body to grasp (default: first graspable)");
  cmd->add_option("--pose", options.pose, "Hand pose in the world: tx,ty,tz,qw,qx,qy,qz (mm)");
  cmd->add_option("--dofs", options.dofs, "DOF values, comma-separated (rad or mm)");
  cmd->add_flag("--autograsp", options.autograsp, "Close the hand until it stops (GraspIt!'s)");
  cmd->add_option("--gws", options.gws, "Grasp wrench space: L1 or Linf")
      ->default_val(std::string(nameOf(GraspRequest{}.wrenchSpace.type)));
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runGrasp(const GraspOptions& options, std::ostream& out) {
  const WrenchSpaceType gws = parseGws(options.gws);  // before the (slower) load
  World world = loadWorldFile(options.world, options.load.options());
  const int robot = chooseHand(world, options.robot);
  const BodyRef object = findObject(world, options.object);
  if (!options.pose.empty()) world.setRobotPose(robot, parsePose(options.pose));
  if (!options.dofs.empty()) {
    world.setDofValues(robot, parseNumberList(options.dofs, "--dofs"));
  }
  const json start_collisions = handCollisions(world, robot);
  std::vector<Contact> contacts;
  std::optional<AutoGraspResult> closed;
  if (options.autograsp) {
    closed = autoGrasp(world, robot);
    contacts = closed->contacts;
  } else {
    contacts = robotContacts(world, robot);
  }
  // Only the contacts with the object make the grasp; others are reported with it too.
  GraspRequest request;
  request.wrenchSpace.type = gws;
  Grasp grasp = analyzeGrasp(world, robot, object, contacts, request);
  json j = graspJson(world, grasp);
  // GraspIt!'s qhull options: `grasp` promises GraspIt!'s figures.
  j["epsilon_method"] = epsilonMethodName(request.wrenchSpace.method);
  j["start_collisions"] = start_collisions;
  if (closed) j["autograsp"] = {{"ended", nameOf(closed->end)}, {"steps", closed->iterations}};
  if (options.json) {
    out << j.dump(2) << "\n";
  } else {
    printText(j, out);
  }
  return 0;
}

}  // namespace graspkit::cli
