#include "serve/editor_session.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>

#include <fmt/format.h>

#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/host/simulation_task.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/io/gltf/gltf_file.hpp"
#include "graspkit/planning/eigengrasp_map.hpp"
#include "graspkit/render/image.hpp"
#include "graspkit/render/render.hpp"
#include "support/scene_frames.hpp"
#include "support/simulation_report.hpp"

namespace graspkit::cli {

using nlohmann::json;

// A plan run in the background: the planner works on a copy of the world and reports here.
struct EditorSession::PlanRun {
  std::thread thread;
  std::atomic<bool> stop{false};
  mutable std::mutex mutex;  // the fields below
  bool running = true;
  PlannerProgress progress;
  double seconds = 0.0;  // the budget asked, 0 for a step budget
  std::optional<host::PlanResult> result;
  std::string error;
  std::atomic<bool> collected{false};  // the thread is done with the session
};

namespace {

RequestError badArgument(const std::string& message) {
  return RequestError(400, message);
}

const json& member(const json& args, const char* key) {
  if (!args.contains(key)) throw badArgument(fmt::format("'{}' is missing", key));
  return args.at(key);
}

double numberIn(const json& value, const char* key) {
  if (!value.is_number()) throw badArgument(fmt::format("'{}' must be a number", key));
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw badArgument(fmt::format("'{}' must be finite", key));
  return x;
}

std::vector<double> numbers(const json& args, const char* key, std::size_t size) {
  const json& list = member(args, key);
  if (!list.is_array() || list.size() != size)
    throw badArgument(fmt::format("'{}' must be a list of {} numbers", key, size));
  std::vector<double> out;
  for (const json& v : list) out.push_back(numberIn(v, key));
  return out;
}

double optionalNumber(const json& args, const char* key, double fallback, double low, double high) {
  if (!args.contains(key)) return fallback;
  const double x = numberIn(args.at(key), key);
  if (x < low || x > high)
    throw badArgument(fmt::format("'{}' must lie in [{}, {}], not {}", key, low, high, x));
  return x;
}

json metres(const Vector3& v) {
  return {v.x() / 1000.0, v.y() / 1000.0, v.z() / 1000.0};
}
json vec(const Vector3& v) {
  return {v.x(), v.y(), v.z()};
}

json poseJson(const Transform& pose) {
  const Quaternion q(pose.linear());
  return {{"translation", vec(pose.translation())}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

Transform poseFrom(const json& args) {
  const std::vector<double> t = numbers(args, "translation", 3);
  const std::vector<double> q = numbers(args, "quaternion", 4);
  const Vector3 translation(t[0], t[1], t[2]);
  if (const char* why = translationProblem(translation))
    throw badArgument(fmt::format("the translation {}", why));
  const std::optional<Quaternion> rotation = unitQuaternion(q[0], q[1], q[2], q[3]);
  if (!rotation) throw badArgument("the quaternion is zero: it names no rotation");
  return makeTransform(translation, *rotation);
}

std::vector<BodyRef> handBodies(const World& world, int hand) {
  std::vector<BodyRef> out;
  for (const BodyRef& b : worldBodies(world))
    if (b.isLink() && b.index == hand) out.push_back(b);
  return out;
}

// A camera the page describes (metres, as three.js has it): eye, target, up, vertical fov.
ViewCamera cameraFrom(const json& camera) {
  const std::vector<double> p = numbers(camera, "position", 3);
  const std::vector<double> t = numbers(camera, "target", 3);
  const std::vector<double> u = numbers(camera, "up", 3);
  const double fov = optionalNumber(camera, "fov", 45.0, 1.0, 170.0);
  const Vector3 eye = Vector3(p[0], p[1], p[2]) * 1000.0;
  const Vector3 forward = Vector3(t[0], t[1], t[2]) * 1000.0 - eye;
  Vector3 up(u[0], u[1], u[2]);
  if (forward.norm() < 1e-9) throw badArgument("the camera's target is its position");
  const Vector3 z = -forward.normalized();
  Vector3 x = up.cross(z);
  if (x.norm() < 1e-9) x = Vector3::UnitX().cross(z);
  if (x.norm() < 1e-9) x = Vector3::UnitY().cross(z);
  x.normalize();
  Matrix3 rotation;
  rotation.col(0) = x;
  rotation.col(1) = z.cross(x);
  rotation.col(2) = z;
  return {eye, Quaternion(rotation), fov * 3.14159265358979323846 / 180.0};
}

// DOF values set by hand: a DOF that moves drives its joints through the coupling again, so a
// finger whose clutch broke away in a close (the Barrett's) follows its slider.
void setDofsByHand(World& world, int hand, std::span<const double> values) {
  const Robot& robot = world.robot(hand);
  const auto now = robot.dofValues();
  for (std::size_t d = 0; d < values.size(); ++d) {
    if (values[d] == now[d]) continue;
    for (int joint : robot.model().dofs[d].joints)
      if (robot.breakaway()[static_cast<std::size_t>(joint)].engaged)
        world.setBreakaway(hand, joint, BreakawayState{});
  }
  world.setDofValues(hand, values);
}

// The shortest text that reads back as the same double.
std::string fixed(double v) {
  return fmt::format("{}", v);
}

std::string numberList(std::span<const double> values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ", ") + fixed(v);
  return text;
}

// The world file a plan's grasps stand on: the first grasp's world (plan --out writes them
// beside the plan), else the planned world. Empty when the plan names neither.
std::filesystem::path planWorldFile(const std::filesystem::path& plan) {
  std::ifstream in(plan);
  const json j = json::parse(in, nullptr, false);
  if (!j.is_object()) return {};
  if (j.contains("world_files") && j["world_files"].is_array() && !j["world_files"].empty() &&
      j["world_files"][0].is_string())
    return plan.parent_path() /
           std::filesystem::path(j["world_files"][0].get<std::string>()).filename();
  if (j.contains("world") && j["world"].is_string())
    return plan.parent_path() / j["world"].get<std::string>();
  return {};
}

}  // namespace

EditorSession::EditorSession(const std::filesystem::path& input, EditorOptions options)
    : options_(std::move(options)) {
  open(input);
}

EditorSession::~EditorSession() {
  if (plan_ && plan_->thread.joinable()) {
    plan_->stop = true;
    plan_->thread.join();
  }
}

void EditorSession::open(const std::filesystem::path& input) {
  std::vector<EditorGrasp> grasps;
  host::WorldSession session;
  if (isDatasetFile(input) || isPlanFile(input)) {
    std::vector<SceneFrame> frames = loadFrames({input, options_.load, false, 0, 0});
    session.world = frames.front().world.clone();
    session.file = planWorldFile(input);
    for (SceneFrame& frame : frames) {
      const int hand = host::defaultHand(frame.world);
      grasps.push_back({frame.name, handConfigurationOf(frame.world, hand), frame.summary});
    }
  } else {
    session = host::WorldSession::load(input, options_.load);
  }
  const int hand = host::defaultHand(session.world);
  std::optional<BodyRef> object;
  if (session.world.firstGraspable()) object = host::defaultObject(session.world);
  session_ = std::move(session);
  hand_ = hand;
  object_ = object;
  grasps_ = std::move(grasps);
  undo_.clear();
  redo_.clear();
  lastGroup_.clear();
}

const BodyRef& EditorSession::object() const {
  if (!object_)
    throw RequestError(409,
                       "the world has no graspable body: there is no grasp to plan or validate");
  return *object_;
}

const std::vector<std::string>& EditorSession::actionNames() {
  static const std::vector<std::string> names = {
      "state",       "pose",      "dofs",   "eigengrasps", "autograsp", "open",    "approach",
      "undo",        "redo",      "save",   "load",        "picture",   "script",  "plan",
      "plan_status", "plan_stop", "grasps", "show_grasp",  "validate",  "simulate"};
  return names;
}

json EditorSession::act(std::string_view name, const json& args) {
  if (!args.is_object()) throw badArgument("the request body must be a JSON object");
  // Long runs work on a copy of the world, outside the lock: the page stays responsive.
  if (name == "validate") return validate(args);
  if (name == "simulate") return simulate(args);
  if (name == "picture") return picture(args);
  std::lock_guard lock(mutex_);
  if (name == "plan_status") return planStatus();
  if (name == "state") return state();
  if (args.contains("group") && !args["group"].is_string())
    throw badArgument("'group' must be a string");
  if (args.contains("preview") && !args["preview"].is_boolean())
    throw badArgument("'preview' must be true or false");
  const World& now = session_.world;
  if (name == "pose") {
    World next = now.clone();
    next.setRobotPose(hand_, poseFrom(args));
    return changed("pose", args, std::move(next));
  }
  if (name == "dofs") {
    const std::vector<double> values =
        numbers(args, "values", static_cast<std::size_t>(now.robot(hand_).dofCount()));
    World next = now.clone();
    setDofsByHand(next, hand_, values);
    return changed("dofs", args, std::move(next));
  }
  if (name == "eigengrasps") {
    const EigengraspMap map(now.robot(hand_).model());
    const std::vector<double> a = numbers(args, "amplitudes", static_cast<std::size_t>(map.size()));
    const Eigen::VectorXd dofs =
        map.dofs(Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size())));
    World next = now.clone();
    setDofsByHand(next, hand_, std::span<const double>(dofs.data(), dofs.size()));
    return changed("eigengrasps", args, std::move(next));
  }
  if (name == "autograsp" || name == "open" || name == "approach") {
    World next = now.clone();
    AutoGraspResult motion;
    if (name == "approach") {
      if (anyCollision(next, handBodies(next, hand_)))
        throw RequestError(409, "the hand is in collision: move it out before approaching");
      motion = approachToContact(next, hand_);
    } else {
      AutoGraspOptions close;
      close.speedFactor = name == "open" ? -1.0 : 1.0;
      motion = autoGrasp(next, hand_, close);
    }
    return changed(nullptr, args, std::move(next),
                   {{"ended", nameOf(motion.end)}, {"steps", motion.iterations}});
  }
  if (name == "undo" || name == "redo") return undo(name == "redo");
  if (name == "save") return save(args);
  if (name == "load") return load(args);
  if (name == "script") return script(args);
  if (name == "plan") return plan(args);
  if (name == "plan_stop") return planStop();
  if (name == "grasps") return grasps();
  if (name == "show_grasp") return showGrasp(args);
  throw RequestError(
      404, fmt::format("no action '{}' (the actions: {})", name, fmt::join(actionNames(), ", ")));
}

// Makes `next` the world, remembering the one before for undo (requests that carry the same
// `group` as the last, a drag's, share one step), and answers the new state.
json EditorSession::changed(const char* kind, const json& args, World next, json extra) {
  const std::string group = args.contains("group") ? args["group"].get<std::string>() : "";
  const bool sameStep = kind != nullptr && !group.empty() && group == lastGroup_;
  if (!sameStep) {
    undo_.push_back(session_.world.clone());
    if (undo_.size() > options_.undoDepth) undo_.erase(undo_.begin());
  }
  lastGroup_ = kind != nullptr ? group : "";
  redo_.clear();
  session_.world = std::move(next);
  json answer = state(args.value("preview", false));
  for (auto& [key, value] : extra.items()) answer[key] = value;
  return answer;
}

json EditorSession::undo(bool forward) {
  std::vector<World>& from = forward ? redo_ : undo_;
  std::vector<World>& to = forward ? undo_ : redo_;
  if (from.empty()) throw RequestError(409, forward ? "nothing to redo" : "nothing to undo");
  to.push_back(std::move(session_.world));
  session_.world = std::move(from.back());
  from.pop_back();
  lastGroup_.clear();
  return state();
}

json EditorSession::state(bool preview) const {
  const World& world = session_.world;
  const Robot& robot = world.robot(hand_);
  json bodies = json::object();
  for (const BodyRef& body : worldBodies(world)) {
    const Transform pose = bodyPose(world, body);
    const Quaternion q(pose.linear());
    bodies[bodyName(world, body)] = {{"t", metres(pose.translation())},
                                     {"q", {q.x(), q.y(), q.z(), q.w()}}};
  }
  json handNames = json::array();
  const std::vector<BodyRef> links = handBodies(world, hand_);
  for (const BodyRef& b : links) handNames.push_back(bodyName(world, b));
  json dofs = json::array();
  for (int d = 0; d < robot.dofCount(); ++d) {
    const Dof& dof = robot.model().dofs[static_cast<std::size_t>(d)];
    dofs.push_back({{"value", robot.dofValues()[static_cast<std::size_t>(d)]},
                    {"min", dof.min},
                    {"max", dof.max}});
  }
  const EigengraspMap map(robot.model());
  const auto values = robot.dofValues();
  const Eigen::VectorXd a = map.amplitudes(
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())));
  json eigen = json::array();
  for (int i = 0; i < map.size(); ++i)
    eigen.push_back(
        {{"amplitude", a[i]}, {"min", map.minAmplitude(i)}, {"max", map.maxAmplitude(i)}});
  json collisions = json::array();
  for (const CollidingPair& pair : collisionReport(world, {links, false}))
    collisions.push_back({bodyName(world, pair.first), bodyName(world, pair.second)});
  GraspRequest request;
  if (preview) request.wrenchSpace.method = HullMethod::NearestFacet;
  json contacts = json::array();
  int others = 0;
  // A bare hand (no object) has no grasp: its contacts are all "others", its quality null.
  json quality = {{"epsilon", nullptr},
                  {"volume", nullptr},
                  {"force_closure", false},
                  {"contacts", 0},
                  {"method", epsilonMethodName(request.wrenchSpace.method)}};
  const std::vector<Contact> touching = robotContacts(world, hand_);
  if (!object_) others = static_cast<int>(touching.size());
  if (object_) {
    const Grasp grasp = analyzeGrasp(world, hand_, *object_, touching, request);
    for (const Contact& c : grasp.contacts) {
      if (!(c.body2 == *object_)) {
        ++others;
        continue;
      }
      contacts.push_back({{"link", bodyName(world, c.body1)},
                          {"point", metres(c.position2)},
                          {"normal", vec(c.normal)},
                          {"mu", c.mu}});
    }
    quality["epsilon"] = grasp.epsilon;
    quality["volume"] = grasp.volume;
    quality["force_closure"] = grasp.forceClosure;
    quality["contacts"] = contacts.size();
  }
  return {{"world", session_.file.filename().string()},
          {"hand",
           {{"name", robot.name()},
            {"pose", poseJson(robot.pose())},
            {"dofs", dofs},
            {"eigengrasps", eigen},
            {"bodies", handNames}}},
          {"object", object_ ? json(bodyName(world, *object_)) : json(nullptr)},
          {"bodies", bodies},
          {"collisions", collisions},
          {"contacts", contacts},
          {"other_contacts", others},
          {"quality", quality},
          {"undo", undo_.size()},
          {"redo", redo_.size()},
          {"grasps", grasps_.size()}};
}

namespace {

// A path the request names, checked against the folders the server may use: refused with 403.
std::filesystem::path checkedPath(const json& args, const lua::PathPolicy& files, bool write) {
  const json& file = member(args, "file");
  if (!file.is_string() || file.get<std::string>().empty())
    throw badArgument("'file' must be a file name");
  const std::filesystem::path path = file.get<std::string>();
  if (write ? files.mayWrite(path) : files.mayRead(path)) return path;
  const auto& folders = write ? files.writable() : files.readable();
  std::string list;
  for (const auto& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  if (write && folders.empty())
    throw RequestError(403,
                       fmt::format("{}: saving is off (start graspkit serve with --allow-write "
                                   "DIR to save below DIR)",
                                   path.string()));
  throw RequestError(403, fmt::format("{}: not below the folders graspkit serve may {} ({}; add "
                                      "one with {})",
                                      path.string(), write ? "write" : "read", list,
                                      write ? "--allow-write" : "--allow-read"));
}

}  // namespace

json EditorSession::save(const json& args) {
  const std::filesystem::path file = checkedPath(args, options_.files, true);
  session_.save(file);  // atomically, as GraspIt! writes worlds
  return {{"saved", file.string()}};
}

json EditorSession::load(const json& args) {
  const std::filesystem::path file = checkedPath(args, options_.files, false);
  if (plan_ && !plan_->collected)
    throw RequestError(409, "a plan is running: stop it before loading another world");
  // Every file the load reads is held to the same folders, not only the one named: the robots,
  // bodies and meshes a world names, a plan's worlds, a dataset's hand and object. A refusal
  // that ends the load is a 403, as for the named file. (Searches ask the guard too, and take a
  // refused place as empty: only the refusal that reaches here counts.)
  static constexpr std::string_view kRefused = "not below the folders graspkit serve may read";
  try {
    ScopedReadGuard guard([this, &file](const std::filesystem::path& read) {
      if (options_.files.mayRead(read)) return;
      throw Error(
          SourceLocation{read.string()},
          fmt::format("named by {}, {} (add one with --allow-read)", file.string(), kRefused));
    });
    open(file);  // assigns nothing until the file has loaded
  } catch (const Error& e) {
    if (std::string_view(e.what()).find(kRefused) != std::string_view::npos)
      throw RequestError(403, e.what());
    throw;
  }
  session_.file = file;
  return state();
}

json EditorSession::script(const json& args) const {
  const std::string language = args.value("language", "lua");
  const Robot& robot = session_.world.robot(hand_);
  const Transform& pose = robot.pose();
  const Vector3 t = pose.translation();
  const Quaternion q(pose.linear());
  if (session_.file.empty())
    throw RequestError(409, "the world has no file yet (a plan's grasp): save it first");
  const std::string world = std::filesystem::absolute(session_.file).lexically_normal().string();
  const std::string translation =
      fmt::format("{}, {}, {}", fixed(t.x()), fixed(t.y()), fixed(t.z()));
  const std::string rotation =
      fmt::format("{}, {}, {}, {}", fixed(q.w()), fixed(q.x()), fixed(q.y()), fixed(q.z()));
  const std::string dofs = numberList(robot.dofValues());
  if (language == "lua")
    return {{"language", "lua"},
            {"text", fmt::format("local world = graspkit.load_world({})\n"
                                 "local hand = world:robot(\"{}\")\n"
                                 "hand:set_pose(graspkit.pose({{{}}}, {{{}}}))\n"
                                 "hand:set_dofs({{{}}})\n",
                                 json(world).dump(), robot.name(), translation, rotation, dofs)}};
  if (language == "python")
    return {{"language", "python"},
            {"text", fmt::format("import graspkit\n\n"
                                 "world = graspkit.load_world({})\n"
                                 "hand = world.robot(\"{}\")\n"
                                 "hand.pose = graspkit.pose(({}), ({}))\n"
                                 "hand.set_dofs([{}])\n",
                                 json(world).dump(), robot.name(), translation, rotation, dofs)}};
  throw badArgument(fmt::format("'language' must be lua or python, not '{}'", language));
}

json EditorSession::plan(const json& args) {
  if (plan_ && !plan_->collected) throw RequestError(409, "a plan is already running");
  if (plan_ && plan_->thread.joinable()) plan_->thread.join();
  host::PlanSettings settings;
  settings.seconds = optionalNumber(args, "seconds", 5.0, 0.01, 3600.0);
  if (args.contains("steps")) {
    settings.steps = static_cast<std::int64_t>(optionalNumber(args, "steps", 0, 1, 1e9));
    settings.seconds.reset();
  }
  if (args.contains("energy")) {
    if (!args["energy"].is_string()) throw badArgument("'energy' must be a name");
    settings.energy = args["energy"].get<std::string>();
  }
  settings.seed = static_cast<std::uint64_t>(optionalNumber(args, "seed", 1, 0, 1e15));
  settings.top = static_cast<int>(optionalNumber(args, "top", 10, 1, 1000));
  // One thread by default: the other core keeps the page and the server answering.
  settings.threads = static_cast<int>(optionalNumber(args, "threads", 1, 0, 256));
  auto world = std::make_shared<const World>(session_.world.clone());
  // Checks the settings now, so that a bad one is this request's error, not the run's.
  const BodyRef target = object();
  host::planningRequest(world, hand_, target, settings);
  host::planningBudget(settings);
  auto run = std::make_unique<PlanRun>();
  run->seconds = settings.seconds.value_or(0.0);
  PlanRun* raw = run.get();
  run->thread = std::thread([this, raw, world, settings, target] {
    std::optional<host::PlanResult> result;
    std::string error;
    try {
      result = host::planGrasps(world, hand_, target, settings, [raw](const PlannerProgress& p) {
        std::lock_guard lock(raw->mutex);
        raw->progress = p;
        return !raw->stop.load();
      });
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard lock(mutex_);
    std::lock_guard runLock(raw->mutex);
    raw->running = false;
    raw->error = error;
    if (result) {
      grasps_.clear();
      for (std::size_t i = 0; i < result->grasps.size(); ++i) {
        const PlannedGrasp& g = result->grasps[i];
        grasps_.push_back({fmt::format("grasp {}", i + 1),
                           g.closed,
                           {{"energy", g.energy},
                            {"epsilon", g.epsilon},
                            {"volume", g.volume},
                            {"contacts", g.contacts},
                            {"force_closure", g.forceClosure},
                            {"rank", i + 1}}});
      }
      raw->result = std::move(result);
    }
    raw->collected = true;
  });
  plan_ = std::move(run);
  return {{"started", true}, {"seconds", settings.seconds.value_or(0.0)}};
}

json EditorSession::planStatus() const {
  if (!plan_) return {{"running", false}, {"grasps", grasps_.size()}};
  std::lock_guard lock(plan_->mutex);
  const PlannerProgress& p = plan_->progress;
  json status = {{"running", plan_->running},
                 {"fraction", plan_->running ? p.fraction : 1.0},
                 {"steps", plan_->result ? plan_->result->steps : p.steps},
                 {"seconds", plan_->result ? plan_->result->seconds : p.seconds},
                 {"force_closure", p.forceClosure},
                 {"stopped", plan_->result ? plan_->result->stopped : plan_->stop.load()},
                 {"grasps", grasps_.size()}};
  if (!plan_->error.empty()) status["error"] = plan_->error;
  return status;
}

json EditorSession::planStop() {
  if (plan_) plan_->stop = true;
  return {{"stopping", plan_ != nullptr && !plan_->collected}};
}

json EditorSession::grasps() const {
  json list = json::array();
  for (const EditorGrasp& g : grasps_) {
    json entry = g.summary.is_null() ? json::object() : g.summary;
    entry["name"] = g.name;
    list.push_back(entry);
  }
  return {{"grasps", list}};
}

json EditorSession::showGrasp(const json& args) {
  const double index = numberIn(member(args, "index"), "index");
  if (index != std::floor(index) || index < 0 || index >= static_cast<double>(grasps_.size()))
    throw badArgument(fmt::format("'index' must be a grasp's 0-based index, 0 to {}",
                                  static_cast<int>(grasps_.size()) - 1));
  const EditorGrasp& grasp = grasps_[static_cast<std::size_t>(index)];
  World next = session_.world.clone();
  applyHandConfiguration(next, hand_, grasp.hand);
  json extra = {{"grasp", grasp.summary}};
  extra["grasp"]["name"] = grasp.name;
  return changed(nullptr, args, std::move(next), extra);
}

json EditorSession::validate(const json& args) const {
  ValidationRequest request;
  request.seconds = optionalNumber(args, "seconds", request.seconds, 0.01, 10.0);
  World world;
  {
    std::lock_guard lock(mutex_);
    object();  // refused without one
    world = session_.world.clone();
  }
  return validationJson(host::validateWorld(world, request));
}

// The hand squeezes (autograsp under its controllers) with gravity on: frames of the bodies'
// poses for the page to play back.
json EditorSession::simulate(const json& args) const {
  host::SimulationSettings settings;
  settings.seconds = optionalNumber(args, "seconds", 1.0, 0.01, 5.0);
  settings.autograsp = args.value("autograsp", true);
  settings.every = static_cast<int>(optionalNumber(args, "every", 8, 1, 1000));
  if (args.contains("gravity")) {
    const std::vector<double> g = numbers(args, "gravity", 3);
    settings.gravity = Vector3(g[0], g[1], g[2]);
  }
  World world;
  {
    std::lock_guard lock(mutex_);
    world = session_.world.clone();
  }
  json frames = json::array();
  const std::vector<BodyRef> bodies = worldBodies(world);
  const host::SimulationOutcome outcome =
      host::simulateWorld(world, settings, [&](const World& now) {
        json poses = json::object();
        for (const BodyRef& body : bodies) {
          const Transform pose = bodyPose(now, body);
          const Quaternion q(pose.linear());
          poses[bodyName(now, body)] = {{"t", metres(pose.translation())},
                                        {"q", {q.x(), q.y(), q.z(), q.w()}}};
        }
        frames.push_back({{"time", now.time()}, {"bodies", poses}});
      });
  return {
      {"frames", frames}, {"completed", outcome.completed}, {"stop_reason", outcome.stopReason}};
}

std::string EditorSession::sceneGltf() const {
  std::lock_guard lock(mutex_);
  const std::vector<GltfScene> scenes = {{"world", &session_.world, ""}};
  return gltfBinary(scenes);
}

std::string EditorSession::picturePng(const json& args) const {
  RenderRequest request;
  request.width = static_cast<int>(optionalNumber(args, "width", 800, 16, 4096));
  request.height = static_cast<int>(optionalNumber(args, "height", 600, 16, 4096));
  request.samples = static_cast<int>(optionalNumber(args, "samples", 2, 1, 4));
  World world;
  {
    std::lock_guard lock(mutex_);
    world = session_.world.clone();
  }
  if (args.contains("camera")) {
    request.camera = cameraFrom(args["camera"]);
  } else {
    const std::vector<BodyRef> focus = handAndObject(world);
    request.camera = namedView(world, "auto", focus, double(request.width) / request.height);
  }
  // graspkit render's look: a floor with shadows, colours kept apart and, with contacts
  // marked, the hand in outline so that none is hidden.
  request.floor = true;
  request.focus = handAndObject(world);
  request.separateColours = true;
  if (args.value("contacts", true)) {
    if (object_)
      for (const Contact& c : robotContacts(world, hand_, &*object_)) request.contacts.push_back(c);
    if (!request.contacts.empty()) request.hand = HandStyle::Outline;
  }
  return pngBytes(render(world, request));
}

json EditorSession::picture(const json& args) const {
  const std::filesystem::path file = checkedPath(args, options_.files, true);
  writeFileAtomically(file, picturePng(args));
  return {{"saved", file.string()}};
}

}  // namespace graspkit::cli
