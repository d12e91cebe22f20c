// graspkit render: a PNG of a world or of a plan's or dataset's grasps (a contact sheet, or one
// grasp).
#include <cmath>
#include <regex>

#include <fmt/format.h>

#include "commands/render_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/render/render.hpp"
#include "graspkit/render/text.hpp"
#include "support/argument_checks.hpp"
#include "support/scene_frames.hpp"

namespace graspkit::cli {

namespace {

std::pair<int, int> parseSize(const std::string& text) {
  static const std::regex kSize(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(text, m, kSize))
    throw Error(fmt::format("--size: '{}' is not WIDTHxHEIGHT, e.g. 640x480", text));
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 1 || h < 1 || w > 16384 || h > 16384 || w * h > 4096 * 4096)
    throw Error(fmt::format(
        "--size: {}x{}; each side must be 1 to 16384 pixels, the picture at most 4096x4096", w, h));
  return {w, h};
}

// "#rank eps E vol V" from a grasp's summary, for its tile.
std::string labelOf(const SceneFrame& frame) {
  const nlohmann::json& s = frame.summary;
  std::string label = fmt::format("#{}", s.value("rank", 0));
  if (s.contains("epsilon") && s["epsilon"].is_number())
    label += fmt::format(" eps {:.3g}", s["epsilon"].get<double>());
  if (s.contains("volume") && s["volume"].is_number())
    label += fmt::format(" vol {:.3g}", s["volume"].get<double>());
  if (s.contains("held") && s["held"].is_boolean())
    label += s["held"].get<bool>() ? " held" : " let go";
  return label;
}

// The label in the top-left corner, dark on a lightened band so it reads on any scene.
void drawLabel(Image& image, const std::string& label) {
  const int scale = image.width >= 480 ? 2 : 1;
  const auto [w, h] = textSize(label, scale);
  for (int y = 0; y < std::min(h + 4, image.height); ++y)
    for (int x = 0; x < std::min(w + 4, image.width); ++x) {
      auto p = image.pixel(x, y);
      for (auto& c : p) c = static_cast<std::uint8_t>(c + (255 - c) * 7 / 10);
      image.setPixel(x, y, p);
    }
  drawText(image, 2, 2, label, {40, 40, 40}, scale);
}

// --hand: auto draws a grasp (a plan's, or any picture with contacts) in outline, so that no
// finger hides a contact, and a bare world solid.
HandStyle handStyleFor(const RenderOptions& options, const SceneFrame& frame) {
  if (options.hand == "auto")
    return frame.fromPlan || options.contacts ? HandStyle::Outline : HandStyle::Solid;
  const std::optional<HandStyle> style = handStyleNamed(options.hand);
  if (!style)
    throw Error(
        fmt::format("--hand: '{}' is not auto, solid, outline or transparent", options.hand));
  return *style;
}

}  // namespace

ViewCamera chooseCamera(const SceneFrame& frame, const std::string& camera, double aspect) {
  // A plan's worlds keep the planned world's <camera>, which framed the open hand, not the grasp.
  const std::string name = camera == "auto" && frame.fromPlan ? "iso" : camera;
  return namedView(frame.world, name, frame.focus, aspect);
}

void addRenderCommand(CLI::App& app, RenderOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Ray-cast a picture (PNG) of a world, or of a plan's or dataset's grasps as a contact sheet");
  cmd->add_option("input", options.input,
                  "World XML, a plan's JSON (plan --out) or a grasp dataset (batch's .h5)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--out", options.out, "The PNG to write")->required();
  cmd->add_option("--size", options.size, "Picture size, WIDTHxHEIGHT (a contact sheet's tile)")
      ->capture_default_str();
  cmd->add_option("--camera", options.camera,
                  std::string("The view: ") + kViewNames +
                      " (auto: a world file's <camera> if it has one, else iso)")
      ->capture_default_str();
  cmd->add_flag("--contacts", options.contacts,
                "Mark the hand's contacts with the object and their friction cones");
  cmd->add_option("--grasp", options.grasp, "Plans: only grasp N (1-based)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--top", options.top, "Plans: the first N grasps on the sheet")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--columns", options.columns, "Plans: tiles a row on the sheet (0: square)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_flag("--no-labels", options.noLabels,
                "Plans: no rank, epsilon and volume in each tile's corner");
  cmd->add_flag("--no-floor", options.noFloor,
                "No floor under the hand and object, and so no shadows");
  cmd->add_option("--hand", options.hand,
                  "How the hand is drawn: solid, outline (edges over a faint fill) or "
                  "transparent; auto: outline for a plan's grasps and with --contacts, else solid")
      ->check(CLI::IsMember({"auto", "solid", "outline", "transparent"}))
      ->capture_default_str();
  cmd->add_flag("--file-colours", options.fileColours,
                "Keep the files' colours even where the hand's is alike the object's");
  cmd->add_option("--samples", options.samples, "Rays per pixel side (2: 4 rays, smoother edges)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  addLoadFlags(*cmd, options.load);
}

int runRender(const RenderOptions& options, std::ostream& out) {
  const auto [width, height] = parseSize(options.size);
  FrameSource source{options.input, options.load.options(), options.contacts, options.grasp,
                     options.top};
  const std::vector<SceneFrame> frames = loadFrames(source);
  // A sheet of 20 full-size tiles would not fit in memory; refuse before drawing any.
  if (static_cast<double>(width) * height * static_cast<double>(frames.size()) > 64e6)
    throw Error(
        fmt::format("--size {}x{} for {} grasps makes a sheet over 64 million pixels; "
                    "use a smaller --size or --top",
                    width, height, frames.size()));
  std::vector<Image> tiles;
  for (const SceneFrame& frame : frames) {
    RenderRequest request;
    request.width = width;
    request.height = height;
    request.samples = options.samples;
    request.camera = chooseCamera(frame, options.camera, static_cast<double>(width) / height);
    request.contacts = frame.contacts;
    request.floor = !options.noFloor;
    request.focus = frame.focus;
    request.hand = handStyleFor(options, frame);
    request.separateColours = !options.fileColours;
    tiles.push_back(render(frame.world, request));
    if (frame.fromPlan && !options.noLabels) drawLabel(tiles.back(), labelOf(frame));
  }
  const int columns =
      options.columns > 0
          ? options.columns
          : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles.size()))));
  const Image image = tiles.size() == 1 ? tiles.front() : tileImages(tiles, columns);
  writePng(image, options.out);
  out << fmt::format("wrote {} ({}x{}, {} {})\n", options.out.string(), image.width, image.height,
                     tiles.size(), tiles.size() == 1 ? "view" : "grasps, rank order by rows");
  return 0;
}

}  // namespace graspkit::cli
