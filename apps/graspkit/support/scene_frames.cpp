#include "support/scene_frames.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/dataset/dataset_planning.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/gltf/gltf_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"

namespace graspkit::cli {

namespace {

using nlohmann::json;

SceneFrame frameOf(std::string name, World world, bool contacts) {
  SceneFrame frame{std::move(name), std::move(world), {}, {}, {}, false};
  frame.focus = handAndObject(frame.world);
  const GraspSubject subject = graspSubject(frame.world);
  if (contacts && subject.hand && subject.object) {
    const Grasp grasp = analyzeGrasp(frame.world, *subject.hand, *subject.object);
    frame.contacts = grasp.contacts;
    frame.summary = {{"epsilon", grasp.epsilon},
                     {"volume", grasp.volume},
                     {"force_closure", grasp.forceClosure},
                     {"contacts", grasp.contacts.size()}};
  }
  return frame;
}

const json& member(const json& j, const char* key, const std::filesystem::path& file) {
  if (!j.is_object() || !j.contains(key))
    throw Error(SourceLocation{file.string(), 0, key}, fmt::format("the plan has no '{}'", key));
  return j.at(key);
}

Transform poseFrom(const json& pose) {
  const auto t = pose.at("translation").get<std::vector<double>>();
  const auto q = pose.at("quaternion").get<std::vector<double>>();
  if (t.size() != 3 || q.size() != 4) throw Error("a pose needs 3 + 4 numbers");
  const Vector3 translation(t[0], t[1], t[2]);
  if (const char* why = translationProblem(translation))
    throw Error(fmt::format("a pose's translation {}", why));
  const std::optional<Quaternion> rotation = unitQuaternion(q[0], q[1], q[2], q[3]);
  if (!rotation) throw Error("a pose's quaternion is zero or not finite: it names no rotation");
  return makeTransform(translation, *rotation);
}

// The grasps --grasp and --top choose of `count`, as [first, last) (0-based).
std::pair<int, int> chosenGrasps(const FrameSource& source, int count, const char* what) {
  if (source.grasp > count || source.grasp < 0)
    throw Error(fmt::format("--grasp {}: the {} {} has {} grasps (1 to {})", source.grasp, what,
                            source.input.string(), count, count));
  if (source.grasp > 0) return {source.grasp - 1, source.grasp};
  return {0, source.top > 0 ? std::min(count, source.top) : count};
}

// A plan without world files: its world, with the hand moved to each grasp's closed posture.
World graspWorldFromPlan(const World& base, const json& plan, const json& grasp) {
  World world = base.clone();
  const std::string robotName = plan.value("robot", "");
  const std::optional<int> robot = world.findRobot(robotName);
  if (!robot) throw Error(fmt::format("the plan's robot '{}' is not in its world", robotName));
  const bool closed = grasp.contains("closed_pose");
  world.setRobotPose(*robot, poseFrom(grasp.at(closed ? "closed_pose" : "pose").at("world")));
  const auto dofs = grasp.at(closed ? "closed_dofs" : "dofs").get<std::vector<double>>();
  world.setDofValues(*robot, dofs);
  return world;
}

std::vector<SceneFrame> planFrames(const FrameSource& source) {
  const std::filesystem::path& file = source.input;
  const json plan = json::parse(readInputFile(file), nullptr, false);
  if (plan.is_discarded())
    throw Error(SourceLocation{file.string(), 0, {}}, "not valid JSON (a plan from plan --json)");
  if (!plan.is_object())
    throw Error(SourceLocation{file.string(), 0, {}},
                "not a plan: a plan is a JSON object with \"grasps\" (from plan --out)");
  const json& grasps = member(plan, "grasps", file);
  if (!grasps.is_array()) throw Error(SourceLocation{file.string(), 0, "grasps"}, "not a list");
  const int count = static_cast<int>(grasps.size());
  if (count == 0)
    throw Error(SourceLocation{file.string(), 0, "grasps"},
                "the plan holds no grasps: nothing to show");
  const auto [first, last] = chosenGrasps(source, count, "plan");
  // The plan's file names: since schema 3 relative to the plan file's folder (or absolute);
  // before, as plan was run (the working folder's, else the plan's folder).
  const json& worldName = member(plan, "world", file);
  if (!worldName.is_string())
    throw Error(SourceLocation{file.string(), 0, "world"}, "not a file name");
  const json* version = plan.contains("schema_version") ? &plan["schema_version"] : nullptr;
  const int schema = version && version->is_number_integer() ? version->get<int>() : 0;
  std::filesystem::path planned = worldName.get<std::string>();
  if (schema >= 3 || !std::filesystem::exists(planned)) planned = file.parent_path() / planned;
  LoadOptions load = source.load;
  // Before schema 3 the worlds plan --out wrote named their models as the planned world did
  // (relative to its root), so that world's folder and its parents are searched after --root.
  // Since, they name them so that they load from anywhere (io/graspit/world_file.hpp).
  if (schema < 3) {
    for (auto folder = std::filesystem::absolute(planned).parent_path();;
         folder = folder.parent_path()) {
      load.roots.push_back(folder);
      if (folder == folder.parent_path()) break;
    }
  }
  const bool hasWorlds = plan.contains("world_files") && plan["world_files"].is_array() &&
                         static_cast<int>(plan["world_files"].size()) == count;
  std::optional<World> base;
  if (!hasWorlds) base = loadWorldFile(planned, load);
  std::vector<SceneFrame> frames;
  for (int i = first; i < last; ++i) {
    const json& grasp = grasps[static_cast<std::size_t>(i)];
    World world;
    try {
      if (hasWorlds) {
        // plan --out writes the worlds beside the JSON; the names it lists are as it was run.
        const std::filesystem::path listed =
            plan["world_files"][static_cast<std::size_t>(i)].get<std::string>();
        world = loadWorldFile(file.parent_path() / listed.filename(), load);
      } else {
        world = graspWorldFromPlan(*base, plan, grasp);
      }
    } catch (const json::exception& e) {
      throw Error(SourceLocation{file.string(), 0, fmt::format("grasps[{}]", i)},
                  fmt::format("not a grasp plan --out writes: {}", e.what()));
    }
    SceneFrame frame = frameOf(fmt::format("grasp {}", i + 1), std::move(world), source.contacts);
    for (const char* key : {"energy", "epsilon", "volume", "contacts", "force_closure"})
      if (grasp.is_object() && grasp.contains(key)) frame.summary[key] = grasp[key];
    frame.summary["rank"] = i + 1;
    frame.fromPlan = true;
    frames.push_back(std::move(frame));
  }
  return frames;
}

// A grasp dataset (graspkit batch): each grasp's world as datasetGraspWorld puts it back, the
// hand over the object at the origin. The grasp is measured again, and must give the epsilon,
// force closure and contact count the file holds: a hand or object file changed since, or a
// hand loaded with other options than batch's (--palm, materials, --mjcf-exact-meshes), would
// otherwise show, or validate, a grasp that was never planned.
std::vector<SceneFrame> datasetFrames(const FrameSource& source) {
  const std::filesystem::path& file = source.input;
  const GraspDataset dataset = loadGraspDataset(file);
  const int count = static_cast<int>(dataset.grasps.size());
  if (count == 0)
    throw Error(SourceLocation{file.string(), 0, "grasps"},
                "the dataset holds no grasps: nothing to show");
  const auto [first, last] = chosenGrasps(source, count, "dataset");
  DatasetRequest request;
  request.hand = dataset.handFile;
  request.object = dataset.objectFile;
  request.load = source.load;
  request.loadedHand = std::make_shared<const World>(loadAnyFile(request.hand, request.load));
  std::vector<SceneFrame> frames;
  for (int i = first; i < last; ++i) {
    const DatasetGrasp& saved = dataset.grasps[static_cast<std::size_t>(i)];
    SceneFrame frame{
        fmt::format("grasp {}", i + 1), datasetGraspWorld(request, saved), {}, {}, {}, true};
    frame.focus = handAndObject(frame.world);
    const Grasp again = analyzeGrasp(frame.world, 0, BodyRef::body(0));
    if (again.forceClosure != saved.forceClosure ||
        !(std::abs(again.epsilon - saved.epsilon) <= 1e-9) ||
        again.contacts.size() != saved.contactPoints.size())
      throw Error(SourceLocation{file.string(), 0, fmt::format("grasps[{}]", i)},
                  fmt::format("grasp {} measures epsilon {:.6g} with {} contacts here, the dataset "
                              "holds {:.6g} with {}: {} or {} changed since, or batch loaded the "
                              "hand with other options (its manifest lists them as "
                              "hand_options): give the same",
                              i + 1, again.epsilon, again.contacts.size(), saved.epsilon,
                              saved.contactPoints.size(), dataset.handFile, dataset.objectFile));
    if (source.contacts) frame.contacts = again.contacts;
    frame.summary["epsilon"] = saved.epsilon;
    frame.summary["volume"] = saved.volume;
    frame.summary["force_closure"] = saved.forceClosure;
    frame.summary["contacts"] = saved.contactPoints.size();
    if (saved.held >= 0) frame.summary["held"] = saved.held == 1;
    frame.summary["rank"] = i + 1;
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace

std::string frameExtras(const SceneFrame& frame) {
  json contacts = json::array();
  for (const Contact& c : frame.contacts) {
    const Vector3 p = c.position2 / 1000.0;
    contacts.push_back({{"point", {p.x(), p.y(), p.z()}},
                        {"normal", {c.normal.x(), c.normal.y(), c.normal.z()}},
                        {"mu", c.mu}});
  }
  const Vector3 centre = boundingSphere(frame.world, frame.focus).centre / 1000.0;
  return json{{"name", frame.name},
              {"centre", {centre.x(), centre.y(), centre.z()}},
              {"summary", frame.summary.is_null() ? json::object() : frame.summary},
              {"contacts", contacts}}
      .dump();
}

std::string framesGltf(const std::vector<SceneFrame>& frames) {
  std::vector<std::string> extras;
  for (const SceneFrame& frame : frames) extras.push_back(frameExtras(frame));
  std::vector<GltfScene> scenes;
  for (std::size_t i = 0; i < frames.size(); ++i)
    scenes.push_back({frames[i].name, &frames[i].world, extras[i]});
  return gltfBinary(scenes);
}

bool isPlanFile(const std::filesystem::path& file) {
  if (file.extension() == ".json") return true;
  std::ifstream in(file);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  return c == '{' || c == '[';
}

bool isDatasetFile(const std::filesystem::path& file) {
  static constexpr char kSignature[] = "\x89HDF\r\n\x1a\n";
  std::ifstream in(file, std::ios::binary);
  char head[8] = {};
  return in.read(head, 8) && std::equal(head, head + 8, kSignature);
}

std::vector<SceneFrame> loadFrames(const FrameSource& source) {
  if (isDatasetFile(source.input)) return datasetFrames(source);
  if (isPlanFile(source.input)) return planFrames(source);
  if (source.grasp > 0)
    throw Error(fmt::format("--grasp picks a grasp of a plan or a dataset; {} is a world",
                            source.input.string()));
  const LoadOptions& load = source.load;
  std::vector<SceneFrame> frames;
  frames.push_back(
      frameOf(source.input.stem().string(), loadWorldFile(source.input, load), source.contacts));
  return frames;
}

}  // namespace graspkit::cli
