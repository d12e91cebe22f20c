// graspkit info FILE: what a body, robot or world file holds, and the link poses of its robots.

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands/info_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/plugin/registry.hpp"
#include "support/argument_checks.hpp"
#include "support/robot_choice.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

json vec(const Vector3& v) {
  return json::array({v.x(), v.y(), v.z()});
}
json quat(const Transform& t) {
  const Quaternion q(t.linear());
  return json::array({q.w(), q.x(), q.y(), q.z()});
}
json pose(const std::string& name, const Transform& t) {
  return {{"name", name}, {"translation", vec(t.translation())}, {"quaternion", quat(t)}};
}

json bodyJson(const Body& body) {
  const BodyModel& m = *body.model;
  json j = pose(body.name, body.pose);
  j["kind"] = nameOf(body.kind);
  j["file"] = m.file.string();
  j["material"] = std::string(nameOf(m.material));
  j["triangles"] = m.mesh->triangleCount();
  j["mass"] = m.mass;
  j["cog"] = vec(m.cog);
  j["inertia"] = json::array();
  for (int k = 0; k < 9; ++k) j["inertia"].push_back(m.inertia(k / 3, k % 3));
  j["max_radius"] = m.maxRadius;
  return j;
}

// Who provided the robot's type: the plugin's name, version and file, or the engine itself.
json typeProviderJson(const RobotModel& m) {
  json j = {{"description", m.typeProvider.empty() ? "built in" : m.typeProvider}};
  const auto from = Registry::global().provenance(FactoryKind::RobotType, m.type);
  if (m.typeProvider != "generic fallback" && from && !from->plugin.empty()) {
    j["plugin"] = from->plugin;
    j["version"] = from->version;
    j["file"] = from->file.string();
  }
  return j;
}

json robotJson(const Robot& robot) {
  const RobotModel& m = robot.model();
  json j = {{"name", robot.name()}, {"type", m.type}, {"file", m.file.string()}};
  j["type_provider"] = typeProviderJson(m);
  j["dof_values"] = std::vector<double>(robot.dofValues().begin(), robot.dofValues().end());
  j["dofs"] = json::array();
  for (const Dof& dof : m.dofs) {
    j["dofs"].push_back({{"type", std::string(1, dofTypeLetter(dof.type))},
                         {"min", dof.min},
                         {"max", dof.max},
                         {"default_velocity", dof.defaultVelocity},
                         {"closes", dof.defaultVelocity < 0.0 ? "-" : "+"},
                         {"joints", dof.joints}});
  }
  j["base"] = pose(m.name + "Base", robot.pose());
  j["base"]["material"] = std::string(nameOf(m.palm->material));
  j["base"]["triangles"] = m.palm->mesh->triangleCount();
  j["chains"] = json::array();
  for (std::size_t c = 0; c < m.chains.size(); ++c) {
    const KinematicChain& chain = m.chains[c];
    json links = json::array();
    for (std::size_t l = 0; l < chain.links.size(); ++l) {
      json link = pose(chain.links[l].name, robot.linkPose(c, l));
      link["material"] = std::string(nameOf(chain.links[l].body->material));
      link["triangles"] = chain.links[l].body->mesh->triangleCount();
      links.push_back(link);
    }
    json joints = json::array();
    for (std::size_t k = 0; k < chain.joints.size(); ++k) {
      const Joint& joint = chain.joints[k];
      joints.push_back({{"type", joint.type == JointType::Revolute ? "revolute" : "prismatic"},
                        {"dof", joint.dof},
                        {"value", robot.jointValues()[chain.firstJoint + k]},
                        {"min", joint.min},
                        {"max", joint.max}});
    }
    j["chains"].push_back({{"joints", joints}, {"links", links}});
  }
  // The link pairs collision detection never checks beyond one chain's links and the palm with
  // each chain's first link: the file's own, and those the hand setup switched off (with why).
  auto linkName = [&](const LinkRef& ref) {
    return ref.isBase() ? m.name + "Base" : m.chains[ref.chain].links[ref.link].name;
  };
  j["collision_exclusions"] = json::array();
  for (const CollisionPair& pair : m.disabledCollisions) {
    j["collision_exclusions"].push_back(
        {{"links", {linkName(pair.first), linkName(pair.second)}},
         {"reason",
          pair.reason.empty() ? std::string("the robot file's <disableCollision>") : pair.reason}});
  }
  j["triangles"] = m.triangleCount();
  j["eigengrasps"] = m.eigengrasps.identity ? 0 : m.eigengrasps.grasps.size();
  j["virtual_contacts"] = m.virtualContacts.size();
  return j;
}

json worldJson(const World& world) {
  json j;
  j["bodies"] = json::array();
  for (const Body& body : world.bodies()) j["bodies"].push_back(bodyJson(body));
  j["robots"] = json::array();
  for (int r = 0; r < world.robotCount(); ++r) j["robots"].push_back(robotJson(world.robot(r)));
  j["connections"] = json::array();
  for (const Connection& c : world.connections()) {
    j["connections"].push_back({{"parent_robot", c.parentRobot},
                                {"parent_chain", c.parentChain},
                                {"child_robot", c.childRobot},
                                {"mount", c.mountFilename}});
  }
  return j;
}

std::string fixed(const json& array) {
  std::string out;
  for (const auto& v : array)
    out += fmt::format("{}{:.4f}", out.empty() ? "" : " ", v.get<double>());
  return out;
}

void printText(const json& j, std::ostream& out) {
  out << fmt::format("{} bodies, {} robots, {} connections\n", j["bodies"].size(),
                     j["robots"].size(), j["connections"].size());
  for (const auto& b : j["bodies"]) {
    out << fmt::format("body {} ({}, {}): {} triangles, mass {} g, cog [{}], at [{}]\n",
                       b["name"].get<std::string>(), b["kind"].get<std::string>(),
                       b["material"].get<std::string>(), b["triangles"].get<std::size_t>(),
                       b["mass"].get<double>(), fixed(b["cog"]), fixed(b["translation"]));
  }
  for (const auto& r : j["robots"]) {
    out << fmt::format("robot {} (type {}): {} DOFs, {} chains, {} triangles\n",
                       r["name"].get<std::string>(), r["type"].get<std::string>(), r["dofs"].size(),
                       r["chains"].size(), r["triangles"].get<std::size_t>());
    const json& provider = r["type_provider"];
    if (provider.contains("plugin")) {
      out << fmt::format("  type {} from plugin {} ({})\n", r["type"].get<std::string>(),
                         provider["description"].get<std::string>(),
                         provider["file"].get<std::string>());
    } else {
      out << fmt::format("  type {} {}\n", r["type"].get<std::string>(),
                         provider["description"].get<std::string>());
    }
    out << fmt::format("  dof values [{}]\n", fixed(r["dof_values"]));
    std::string closes;
    for (const auto& dof : r["dofs"])
      closes += (closes.empty() ? "" : " ") + dof["closes"].get<std::string>();
    out << fmt::format("  closes     [{}] (+: towards the upper limit)\n", closes);
    out << fmt::format("  {:<28} t [{}]  q [{}]\n", r["base"]["name"].get<std::string>(),
                       fixed(r["base"]["translation"]), fixed(r["base"]["quaternion"]));
    for (const auto& chain : r["chains"]) {
      for (const auto& link : chain["links"]) {
        out << fmt::format("  {:<28} t [{}]  q [{}]\n", link["name"].get<std::string>(),
                           fixed(link["translation"]), fixed(link["quaternion"]));
      }
    }
    for (const auto& pair : r["collision_exclusions"]) {
      out << fmt::format("  never checked: {} - {} ({})\n", pair["links"][0].get<std::string>(),
                         pair["links"][1].get<std::string>(), pair["reason"].get<std::string>());
    }
  }
}

}  // namespace

void addInfoCommand(CLI::App& app, InfoOptions& options) {
  CLI::App* cmd = app.add_subcommand("info", "Describe a body, robot or world file");
  cmd->add_option("file", options.file, "Body, robot or world XML (or a mesh file)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--dofs", options.dofs, "DOF values to set, comma-separated (rad or mm)");
  cmd->add_option("--robot", options.robot,
                  "Which robot --dofs applies to: a name or 0-based index (default: the first)");
  addLoadFlags(*cmd, options.load);
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runInfo(const InfoOptions& options, std::ostream& out) {
  World world = loadAnyFile(options.file, options.load.options());
  // --robot is checked even without --dofs: a wrong name or index must not pass unnoticed.
  const int robot = options.robot.empty() ? 0 : chooseHand(world, options.robot);
  if (!options.dofs.empty()) {
    if (world.robotCount() == 0) throw Error("--dofs: the file has no robot");
    world.setDofValues(robot, parseNumberList(options.dofs, "--dofs"));
  }
  json j = worldJson(world);
  j["file"] = options.file.string();
  if (options.json) {
    out << j.dump(2) << "\n";
  } else {
    printText(j, out);
  }
  return 0;
}

}  // namespace graspkit::cli
