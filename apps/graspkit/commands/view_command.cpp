// graspkit view: one self-contained HTML page showing a world or a plan's grasps in 3-D. The page
// holds the scene as binary glTF (base64) and the viewer script (three.js, bundled at build time),
// so it opens from a file with no network and no server.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands/view_command.hpp"
#include "graspkit/base/error.hpp"
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
  <span id="name"></span>
  <div id="figures"></div>
</div>
)page";

}  // namespace

void addViewCommand(CLI::App& app, ViewOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "view", "Write one self-contained HTML page to look at a world or a plan's grasps in 3-D");
  cmd->add_option("input", options.input, "World XML, or a plan's JSON (plan --out)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--html", options.html, "The page to write")->required();
  cmd->add_option("--top", options.top, "Plans: the first N grasps (all when not given)")
      ->check(CLI::Range(1, 1000000));
  addLoadFlags(*cmd, options.load);
}

int runView(const ViewOptions& options, std::ostream& out) {
  if (kViewerScript == nullptr)
    throw Error(
        "graspkit view: this graspkit was built without the web viewer (it needs node and "
        "npm when it is built; see docs/pictures.md)");
  const std::vector<SceneFrame> frames =
      loadFrames({options.input, options.load, true, 0, options.top});
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
