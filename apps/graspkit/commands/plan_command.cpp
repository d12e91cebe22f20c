// graspkit plan: run a grasp planner on a world and print (or save) the best grasps, each closed
// with autograsp and measured.

#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "commands/plan_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/file_reference.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/base/version.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/grasp/wrench_space.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "support/argument_checks.hpp"
#include "support/progress_reporter.hpp"
#include "support/robot_choice.hpp"
#include "support/simulation_report.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

// The layout of the plan JSON; raised whenever a field changes meaning or goes away. 3: the
// file names (world, object_file, robot_file, world_files) are relative to the plan file's folder
// (or absolute), not to the folder plan ran in.
constexpr int kPlanSchemaVersion = 3;

std::map<std::string, std::string> plannerOptions(const PlanOptions& options) {
  std::map<std::string, std::string> result;
  for (const std::string& item : options.set) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error(fmt::format("--set: '{}' is not KEY=VALUE", item));
    result[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return result;
}

json poseJson(const Transform& pose) {
  const Quaternion q(pose.rotation());
  const Vector3 t = pose.translation();
  return {{"translation", {t.x(), t.y(), t.z()}}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

json vectorJson(const Vector3& v) {
  return {v.x(), v.y(), v.z()};
}

// A contact of the closed hand, in the object's frame: the point on the object and the normal
// pointing into the object (the direction the hand pushes), and which hand link touches.
json contactJson(const World& world, const Transform& objectPose, const Contact& contact) {
  const Transform toObject = objectPose.inverse();
  json link = "palm";
  if (contact.body1.kind == BodyRef::Kind::Link && !contact.body1.link.isBase())
    link = {contact.body1.link.chain, contact.body1.link.link};
  (void)world;
  json j = {{"link", link},
            {"point", vectorJson(toObject * contact.position2)},
            {"normal", vectorJson(-(toObject.linear() * contact.normal))},
            {"mu", contact.mu},
            {"model", nameOf(contact.model)}};
  if (contact.model == ContactModel::SoftFinger) j["torsion"] = contact.torsion;
  return j;
}

json graspJson(const World& world, const Transform& objectPose, const PlannedGrasp& g) {
  const Transform toObject = objectPose.inverse();
  const json open = poseJson(g.pose);
  json grasp = {{"translation", open["translation"]},
                {"quaternion", open["quaternion"]},
                {"dofs", g.dofs},
                {"pose", {{"world", open}, {"object", poseJson(toObject * g.pose)}}},
                {"open_dofs", g.dofs},
                {"energy", g.energy},
                {"evaluated", g.evaluated}};
  if (!g.evaluated) return grasp;
  json contacts = json::array();
  for (const Contact& c : g.contactList) contacts.push_back(contactJson(world, objectPose, c));
  grasp.update(
      {{"closed_pose",
        {{"world", poseJson(g.closed.pose)}, {"object", poseJson(toObject * g.closed.pose)}}},
       {"closed_dofs", g.closed.dofs},
       {"epsilon", g.epsilon},
       {"volume", g.volume},
       {"contacts", g.contacts},
       {"contact_points", contacts},
       {"force_closure", g.forceClosure}});
  return grasp;
}

void printTable(const json& result, std::ostream& out) {
  out << fmt::format(
      "{} grasps ({} force closure) in {} steps, {:.2f} s, {:.0f} steps/s, "
      "{} thread(s), seed {}\n",
      result["grasps"].size(), result["force_closure_count"].get<int>(),
      result["steps"].get<std::int64_t>(), result["seconds"].get<double>(),
      result["steps_per_second"].get<double>(), result["threads"].get<int>(),
      result["seed"].get<std::uint64_t>());
  out << "epsilon by " << result["epsilon_method"].get<std::string>();
  if (result.contains("energy_epsilon_method"))
    out << "; the energy's epsilon by " << result["energy_epsilon_method"].get<std::string>();
  out << "\n";
  const bool validated = result.value("validated", false);
  out << fmt::format("{:>4} {:>11} {:>10} {:>10} {:>8} {:>3} {}  {:<30} {}\n", "rank", "energy",
                     "epsilon", "volume", "contacts", "fc", validated ? " held" : "",
                     "translation (mm)", "quaternion (w x y z)");
  int rank = 1;
  for (const json& g : result["grasps"]) {
    const auto& t = g["translation"];
    const auto& q = g["quaternion"];
    // Held: the directions (of 6) in which the hand held the object's weight.
    const std::string held =
        validated ? fmt::format("{:>5}",
                                fmt::format("{}/6", g["validation"]["directions_held"].get<int>()))
                  : "";
    out << fmt::format("{:>4} {:>11.5g} {:>10.5g} {:>10.5g} {:>8} {:>3} {}  {:<30} {}\n", rank++,
                       g["energy"].get<double>(), g["epsilon"].get<double>(),
                       g["volume"].get<double>(), g["contacts"].get<int>(),
                       g["force_closure"].get<bool>() ? "yes" : "no", held,
                       fmt::format("{:.2f} {:.2f} {:.2f}", t[0].get<double>(), t[1].get<double>(),
                                   t[2].get<double>()),
                       fmt::format("{:.5f} {:.5f} {:.5f} {:.5f}", q[0].get<double>(),
                                   q[1].get<double>(), q[2].get<double>(), q[3].get<double>()));
  }
}

// The files --out writes: <out> (the JSON) and beside it <stem>_<rank>.xml per grasp.
std::filesystem::path worldFileFor(const std::filesystem::path& out, std::size_t rank) {
  return out.parent_path() / fmt::format("{}_{:02}.xml", out.stem().string(), rank);
}

// Refuses an --out that cannot be written before any planning is done: a folder, a missing
// parent folder, or one where a file cannot be created.
void checkOut(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  if (out.empty()) return;
  if (!out.has_filename() || fs::is_directory(out))
    throw Error(fmt::format("--out: '{}' is a folder; give a file name such as {}/plan.json",
                            out.string(), out.string()));
  const fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(folder))
    throw Error(fmt::format("--out: the folder '{}' does not exist", folder.string()));
  const fs::path probe = folder / fmt::format(".{}.probe{}", out.filename().string(), ::getpid());
  {
    std::ofstream file(probe);
    if (!file) throw Error(fmt::format("--out: cannot write in '{}'", folder.string()));
  }
  fs::remove(probe);
}

// One world per grasp (graspWorld: the hand closed as the plan measured it, breakaway state
// included), then the JSON. On any failure the files already written are removed.
void saveOut(const PlanningRequest& request, const std::vector<PlannedGrasp>& grasps, json& result,
             const std::filesystem::path& out) {
  std::vector<std::filesystem::path> written;
  try {
    json files = json::array();
    for (std::size_t i = 0; i < grasps.size(); ++i) {
      const auto file = worldFileFor(out, i + 1);
      saveWorldFile(graspWorld(request, grasps[i]), file);
      written.push_back(file);
      files.push_back(fileReference(file, out.parent_path()));
    }
    result["world_files"] = files;
    writeFileAtomically(out, result.dump(2) + "\n");
  } catch (...) {
    for (const auto& file : written) std::filesystem::remove(file);
    throw;
  }
}

// Labels each grasp as graspkit validate does, on the world the grasp is saved as.
void addValidation(const PlanningRequest& request, const std::vector<PlannedGrasp>& grasps,
                   double seconds, bool quiet, json& result) {
  if (!quiet && !grasps.empty())
    std::cerr << fmt::format("graspkit: validating {} grasps (6 directions x {:g} s each)\n",
                             grasps.size(), seconds);
  ValidationRequest validation;
  validation.seconds = seconds;
  std::vector<World> worlds;
  for (const PlannedGrasp& g : grasps) worlds.push_back(graspWorld(request, g));
  const std::vector<ValidationResult> labels =
      validateGrasps(worlds, request.robot, request.object.index, validation, request.threads);
  int held = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    result["grasps"][i]["validation"] = validationJson(labels[i]);
    held += labels[i].held ? 1 : 0;
  }
  result["validated"] = true;
  result["validation_seconds"] = seconds;
  result["held_count"] = held;
}

std::string progressText(const PlannerProgress& p) {
  const double eta = p.fraction > 0 ? p.seconds * (1.0 - p.fraction) / p.fraction : -1.0;
  std::string text = fmt::format("{:>3.0f}%  {} steps  {} elapsed, {} left", 100.0 * p.fraction,
                                 p.steps, clockTime(p.seconds), clockTime(eta));
  if (p.forceClosure >= 0)
    text += fmt::format("  {} grasps, {} force closure", p.states, p.forceClosure);
  else
    text += fmt::format("  {} states, best energy {:.5g}", p.states, p.bestEnergy);
  return text;
}

}  // namespace

void addPlanCommand(CLI::App& app, PlanOptions& options) {
  const host::PlanSettings defaults;  // every default is the host layer's
  CLI::App* cmd = app.add_subcommand(
      "plan", "Plan grasps with a planner plugin and print the best, each closed and measured");
  cmd->add_option("world", options.world, "World XML")->required()->check(existingFile());
  addLoadFlags(*cmd, options.load);
  cmd->add_option("--robot", options.robot,
                  "The hand: a robot's name or 0-based index (default: the world's first hand)");
  cmd->add_option("--object", options.object, "The body to grasp (default: first graspable)");
  cmd->add_option("--planner", options.planner, "Planner: simann, list, approach or a plugin's")
      ->default_val(defaults.planner);
  cmd->add_option("--energy", options.energy,
                  "Search energy: contact, potential-quality, guided-potential-quality, "
                  "autograsp-quality, strict-autograsp (or GraspIt!'s names)")
      ->default_val(defaults.energy);
  cmd->add_option("--space", options.space,
                  "Hand position space: axis-angle, complete, "
                  "ellipsoid, approach")
      ->default_val(std::string(nameOf(defaults.space)));
  cmd->add_option("--posture", options.posture, "Posture space: eigen or dof")
      ->default_val(std::string(nameOf(defaults.posture)));
  cmd->add_option("--mode", options.mode,
                  "simann mode: restarts (many short searches, each closing its best states; "
                  "any-time; the default) or anneal (GraspIt!'s single search)");
  cmd->add_option("--preset", options.preset,
                  "simann schedule: DEFAULT, LOOP, MODIFIED, STRICT, ONLINE");
  cmd->add_option("--set", options.set, "A planner option KEY=VALUE (repeatable)");
  auto* steps = cmd->add_option(
      "--steps", options.steps,
      fmt::format("Steps in total, every stage included (default {}: GraspIt!'s search length)",
                  host::kDefaultPlanSteps));
  cmd->add_option("--seconds", options.seconds,
                  "Plan for this long (every stage included) instead of a step count")
      ->excludes(steps)
      ->check(positiveFinite());
  cmd->add_option("--threads", options.threads, "Search threads (default: every core)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--seed", options.seed, "Random seed")
      ->check(seedNumber())
      ->default_val(defaults.seed);
  cmd->add_option("--top", options.top, "How many grasps to keep (the best list's size)")
      ->default_val(defaults.top)
      ->check(CLI::Range(1, 10000));
  cmd->add_flag("--validate", options.validate,
                "Label each grasp physically, as graspkit validate does (the weight in 6 "
                "directions, 2 s each)");
  cmd->add_option("--validate-seconds", options.validateSeconds,
                  "--validate: simulated seconds per direction")
      ->default_val(ValidationRequest{}.seconds)
      ->check(positiveFinite());
  cmd->add_flag("--json", options.json, "Print one JSON object");
  cmd->add_option("--out", options.out,
                  "Write the JSON here, and beside it one world file per grasp (the hand "
                  "closed as measured)");
}

// The settings the flags describe; what they leave out is the host layer's default.
host::PlanSettings planSettings(const PlanOptions& options) {
  host::PlanSettings settings;
  settings.planner = options.planner;
  settings.energy = options.energy;
  settings.space = parseNamed<PositionSpace>(options.space, "position space");
  settings.posture = parseNamed<PostureSpace>(options.posture, "posture space");
  settings.mode = options.mode;
  settings.preset = options.preset;
  settings.options = plannerOptions(options);
  settings.steps = options.steps;
  settings.seconds = options.seconds;
  settings.seed = options.seed;
  settings.threads = options.threads.value_or(0);
  settings.top = options.top;
  return settings;
}

int runPlan(const PlanOptions& options, bool quiet, std::ostream& out) {
  checkOut(options.out);
  auto world = std::make_shared<World>(loadWorldFile(options.world, options.load.options()));
  const host::PlanSettings settings = planSettings(options);
  const int robot = chooseHand(*world, options.robot);
  const BodyRef target = chooseObject(*world, options.object);
  // Checked before planning, so that a bad setting fails at once.
  host::planningRequest(world, robot, target, settings);
  host::planningBudget(settings);

  // A hand without virtual contacts plans on contacts derived from its geometry: say so.
  const host::PlanningContacts contacts = host::planningContacts(*world, robot);
  if (contacts.derived && !quiet)
    std::cerr << fmt::format(
        "graspkit: note: {} has no virtual contacts; the planner uses {} derived from its "
        "geometry and closing motion (one per moving link's pad, one on the palm)\n",
        world->robot(robot).name(), contacts.count);

  ProgressReporter progress(ProgressReporter::forStderr(quiet));
  host::PlanResult run =
      host::planGrasps(world, robot, target, settings, [&progress](const PlannerProgress& p) {
        if (p.fraction >= 1.0)
          progress.finish(p.fraction, progressText(p));
        else
          progress.update(p.fraction, progressText(p));
        return true;
      });
  progress.clear();
  const PlanningRequest& request = *run.request;
  const std::size_t contactCount = contacts.count;
  const bool derived = contacts.derived;
  const PlanningBudget budget = host::planningBudget(settings);

  const Body& object = world->bodies()[static_cast<std::size_t>(request.object.index)];
  const WorldRobot& hand = world->worldRobot(request.robot);
  // Files named as the plan file reads them from any folder: relative to its folder, or
  // absolute (base/file_reference.hpp); printed without --out, absolute.
  auto named = [&](const std::filesystem::path& file) {
    return options.out.empty() ? std::filesystem::absolute(file).lexically_normal().string()
                               : fileReference(file, options.out.parent_path());
  };
  json result = {{"schema_version", kPlanSchemaVersion},
                 {"engine_version", engineVersion()},
                 {"world", named(options.world)},
                 {"object", object.name},
                 {"object_file", named(object.model->file)},
                 {"object_pose", poseJson(object.pose)},
                 {"robot", hand.robot.name()},
                 {"robot_file", named(hand.robot.model().file)},
                 {"virtual_contacts", {{"count", contactCount}, {"derived", derived}}},
                 {"planner", options.planner},
                 {"mode", request.options.count("mode") ? request.options.at("mode") : ""},
                 {"energy", canonicalEnergyName(request.energy)},
                 {"space", nameOf(request.position)},
                 {"posture", nameOf(request.posture)},
                 {"steps", run.steps},
                 {"seconds", run.seconds},
                 {"steps_per_second", run.seconds > 0 ? run.steps / run.seconds : 0.0},
                 {"seed", request.seed},
                 {"threads", request.threads},
                 {"grasps", json::array()}};
  if (budget.seconds)
    result["budget"] = {{"seconds", *budget.seconds}};
  else
    result["budget"] = {{"steps", *budget.steps}};
  int forceClosure = 0;
  for (const PlannedGrasp& g : run.grasps) {
    result["grasps"].push_back(graspJson(*world, object.pose, g));
    forceClosure += g.forceClosure ? 1 : 0;
  }
  result["force_closure_count"] = forceClosure;
  // The grasps are measured as GraspIt! measures them; the energy may use another epsilon.
  result["epsilon_method"] = epsilonMethodName(GraspRequest{}.wrenchSpace.method);
  if (const std::string_view m = energyEpsilonMethod(request.energy); !m.empty())
    result["energy_epsilon_method"] = m;
  if (options.validate) addValidation(request, run.grasps, options.validateSeconds, quiet, result);
  if (!options.out.empty()) saveOut(request, run.grasps, result, options.out);
  if (options.json)
    out << result.dump(2) << "\n";
  else
    printTable(result, out);
  return 0;
}

}  // namespace graspkit::cli
