// graspkit view: one self-contained HTML page showing a world or a plan's grasps in 3-D. The page
// holds the scene as binary glTF (base64) and the viewer script (three.js, bundled at build time),
// so it opens from a file with no network and no server.
#include <algorithm>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands/view_command.hpp"

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "support/argument_checks.hpp"
#include "support/scene_frames.hpp"

namespace graspkit::cli {

extern const char* const kViewerScript;  // viewer/build.mjs; null when built without the viewer

namespace {

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t word = 0;
    for (std::size_t k = 0; k < 3; ++k)
      word = word << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) text += k <= n ? kDigits[(word >> (18 - 6 * k)) & 63] : '=';
  }
  return text;
}

// Text for an HTML element's content or a JSON script block: no markup can start inside it.
std::string escapeHtml(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// The viewer's starting camera: the render command's automatic one, in metres.
nlohmann::json cameraJson(const SceneFrame& frame) {
  const ViewCamera camera = chooseCamera(frame, "auto", 4.0 / 3.0);
  const BoundingSphere sphere = boundingSphere(frame.world, frame.focus);
  const Vector3 forward = camera.orientation * -Vector3::UnitZ();
  const Vector3 up = camera.orientation * Vector3::UnitY();
  // The orbit centre is the focus's centre: framing aims the camera at it (a world file's own
  // camera may look elsewhere; then the point straight ahead at the same depth).
  const Vector3 target =
      camera.position + forward * std::max(1.0, (sphere.centre - camera.position).dot(forward));
  const auto metres = [](const Vector3& v) {
    return nlohmann::json{v.x() / 1000.0, v.y() / 1000.0, v.z() / 1000.0};
  };
  return {{"position", metres(camera.position)},
          {"target", metres(target)},
          {"up", {up.x(), up.y(), up.z()}},
          {"fov", camera.heightAngle * 180.0 / 3.14159265358979323846}};
}

constexpr const char* kPageStart = R"page(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="generator" content="graspkit view">
<title>{title}</title>
<style>
  html, body {{ margin: 0; height: 100%; font: 14px system-ui, sans-serif; }}
  #view {{ display: block; width: 100%; height: 100%; }}
  #panel {{ position: absolute; top: 8px; left: 8px; padding: 6px 10px; background: #fffd;
           border: 1px solid #ccc; border-radius: 4px; }}
  #figures {{ color: #333; margin-top: 4px; }}
</style>
</head>
<body>
<canvas id="view"></canvas>
<div id="panel">
  <button id="previous" title="previous (left arrow)">&larr;</button>
  <button id="next" title="next (right arrow)">&rarr;</button>
  <label><input type="checkbox" id="show-contacts" checked> contacts</label>
  <span id="playback" hidden><button id="play">&#9654;</button>
    <input type="range" id="time" min="0" value="0"> <span id="clock"></span></span>
  <span id="name"></span>
  <div id="figures"></div>
</div>
)page";

// The most frames a page plays back: a 20 s run at simulate's defaults has 800.
constexpr std::size_t kMaxTrajectoryFrames = 20000;

const nlohmann::json& field(const nlohmann::json& j, const char* key, const SourceLocation& where) {
  if (!j.is_object() || !j.contains(key))
    throw Error(where, fmt::format("not a simulate --trajectory line: no '{}'", key));
  return j.at(key);
}

Transform poseOf(const nlohmann::json& entry, const SourceLocation& where) {
  const auto t = field(entry, "position", where).get<std::vector<double>>();
  const auto q = field(entry, "orientation_wxyz", where).get<std::vector<double>>();
  if (t.size() != 3 || q.size() != 4) throw Error(where, "a pose needs 3 + 4 numbers");
  const std::optional<Quaternion> rotation = unitQuaternion(q[0], q[1], q[2], q[3]);
  if (!rotation || translationProblem(Vector3(t[0], t[1], t[2])) != nullptr)
    throw Error(where, "a pose that names no place (zero quaternion, or not finite)");
  return makeTransform(Vector3(t[0], t[1], t[2]), *rotation);
}

// Puts `world` in the state one trajectory line holds: the bodies' poses, and each robot's base
// pose, broken-away joints and DOF values.
void applyLine(World& world, const nlohmann::json& line, const SourceLocation& where) {
  for (const nlohmann::json& entry : field(line, "bodies", where)) {
    const std::string name = field(entry, "name", where).get<std::string>();
    auto& bodies = world.bodies();
    const auto body =
        std::find_if(bodies.begin(), bodies.end(), [&](const Body& b) { return b.name == name; });
    if (body == bodies.end())
      throw Error(where,
                  fmt::format("the world has no body '{}': is it the simulated world?", name));
    body->setPose(poseOf(entry, where));
  }
  for (const nlohmann::json& entry : field(line, "robots", where)) {
    const std::string name = field(entry, "name", where).get<std::string>();
    const std::optional<int> robot = world.findRobot(name);
    if (!robot)
      throw Error(where,
                  fmt::format("the world has no robot '{}': is it the simulated world?", name));
    if (entry.contains("position")) world.setRobotPose(*robot, poseOf(entry, where));
    const Robot& r = world.robot(*robot);
    for (std::size_t j = 0; j < r.breakaway().size(); ++j)
      world.setBreakaway(*robot, static_cast<int>(j), BreakawayState{});
    for (const nlohmann::json& joint : entry.value("broken_away", nlohmann::json::array())) {
      const auto pair = joint.get<std::vector<double>>();
      if (pair.size() != 2 || pair[0] < 0 || pair[0] >= static_cast<double>(r.breakaway().size()))
        throw Error(where, "'broken_away' holds [joint, value] pairs of the robot's joints");
      world.setBreakaway(*robot, static_cast<int>(pair[0]), BreakawayState{true, pair[1]});
    }
    const auto dofs = field(entry, "dof_values", where).get<std::vector<double>>();
    if (static_cast<int>(dofs.size()) != r.dofCount())
      throw Error(where, fmt::format("robot '{}' has {} DOFs, the line {}", name, r.dofCount(),
                                     dofs.size()));
    world.setDofValues(*robot, dofs, LimitPolicy::Ignore);
  }
}

// The frames of a trajectory file for the page: time and every body's pose (metres, [x, y, z, w]),
// by the names the glTF nodes carry.
nlohmann::json trajectoryFrames(const World& start, const std::filesystem::path& file) {
  std::istringstream in(readInputFile(file));
  nlohmann::json frames = nlohmann::json::array();
  World world = start.clone();
  const std::vector<BodyRef> bodies = worldBodies(world);
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    if (text.empty()) continue;
    const SourceLocation where{file.string(), number, {}};
    if (frames.size() == kMaxTrajectoryFrames)
      throw Error(where, fmt::format("more than {} frames: pass a larger --every to simulate",
                                     kMaxTrajectoryFrames));
    const nlohmann::json line = nlohmann::json::parse(text, nullptr, false);
    if (line.is_discarded()) throw Error(where, "not JSON (a simulate --trajectory line)");
    try {
      applyLine(world, line, where);
    } catch (const nlohmann::json::exception& e) {
      throw Error(where, fmt::format("not a simulate --trajectory line: {}", e.what()));
    }
    nlohmann::json poses = nlohmann::json::object();
    for (const BodyRef& body : bodies) {
      const Transform pose = bodyPose(world, body);
      const Quaternion q(pose.linear());
      const Vector3 t = pose.translation() / 1000.0;
      poses[bodyName(world, body)] = {{"t", {t.x(), t.y(), t.z()}},
                                      {"q", {q.x(), q.y(), q.z(), q.w()}}};
    }
    frames.push_back({{"time", line.value("time", 0.0)}, {"bodies", poses}});
  }
  if (frames.empty()) throw Error(SourceLocation{file.string(), 0, {}}, "no trajectory lines");
  return frames;
}

}  // namespace

void addViewCommand(CLI::App& app, ViewOptions& options) {
  CLI::App* cmd = app.add_subcommand("view",
                                     "Write one self-contained HTML page to look at a world or a "
                                     "plan's or dataset's grasps in 3-D");
  cmd->add_option("input", options.input,
                  "World XML, a plan's JSON (plan --out) or a grasp dataset (batch's .h5)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--html", options.html, "The page to write")->required();
  cmd->add_option("--top", options.top, "Plans: the first N grasps (all when not given)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--trajectory", options.trajectory,
                  "Worlds: a simulate --trajectory file (JSON lines) to play back")
      ->check(existingFile());
  addLoadFlags(*cmd, options.load);
}

int runView(const ViewOptions& options, std::ostream& out) {
  if (kViewerScript == nullptr)
    throw Error(
        "graspkit view: this graspkit was built without the web viewer (it needs node and "
        "npm when it is built; see docs/pictures.md)");
  const std::vector<SceneFrame> frames =
      loadFrames({options.input, options.load.options(), true, 0, options.top});
  if (!options.trajectory.empty() && frames.front().fromPlan)
    throw Error("--trajectory plays a simulation back on a world file, not on a plan");
  // Contact markers sized by the object, as render sizes them.
  std::vector<BodyRef> object;
  for (const BodyRef& body : frames.front().focus)
    if (body.kind == BodyRef::Kind::Body) object.push_back(body);
  const BoundingSphere sphere = boundingSphere(frames.front().world, object);
  nlohmann::json meta = {{"title", options.input.filename().string()},
                         {"camera", cameraJson(frames.front())},
                         {"markerSize", 0.25 * sphere.radius / 1000.0}};
  // The object's centre (metres) in the first scene, for tools and tests that look at the page.
  for (const BodyRef& body : frames.front().focus) {
    if (body.kind != BodyRef::Kind::Body) continue;
    const Vector3 c = boundingSphere(frames.front().world, std::vector<BodyRef>{body}).centre;
    meta["object"] = {{"name", bodyName(frames.front().world, body)},
                      {"centre", {c.x() / 1000.0, c.y() / 1000.0, c.z() / 1000.0}}};
  }
  if (!options.trajectory.empty())
    meta["trajectory"] = trajectoryFrames(frames.front().world, options.trajectory);
  std::string page = fmt::format(
      kPageStart, fmt::arg("title", escapeHtml("graspkit: " + options.input.filename().string())));
  page += "<script id=\"graspkit-meta\" type=\"application/json\">" + escapeHtml(meta.dump()) +
          "</script>\n";
  page += "<script id=\"graspkit-scene\" type=\"application/octet-stream\">" +
          base64(framesGltf(frames)) + "</script>\n<script>";
  page += kViewerScript;
  page += "</script>\n</body>\n</html>\n";
  writeFileAtomically(options.html, page);
  out << fmt::format("wrote {} ({} scene{}, {:.1f} MB)\n", options.html.string(), frames.size(),
                     frames.size() == 1 ? "" : "s", page.size() / 1e6);
  return 0;
}

}  // namespace graspkit::cli
