// Inventor (.iv) and VRML 2 (.wrl) through Coin3D. Coin parses the scene and tessellates every
// shape node (Cube, Sphere, Cylinder, Cone, face sets, VRML geometry); an SoCallbackAction hands
// us each triangle, which we move into the scene's root frame with the model matrix in effect
// (so Transform, Scale and friends apply) and weld into an indexed mesh. GraspIt! collects its
// triangles the same way, so triangle counts match it one for one.
//
// Coin trusts its input and crashes or hangs on some malformed files, so nothing reaches it
// unchecked: the text is checked for what its recursive parser cannot take (SceneTextCheck),
// and every node is checked just before Coin traverses it (beforeNode, inventor_shape_check).

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <Inventor/SbColor.h>
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPath.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/actions/SoSearchAction.h>
#include <Inventor/elements/SoNormalBindingElement.h>
#include <Inventor/elements/SoNormalElement.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/lists/SoPathList.h>
#include <Inventor/nodes/SoInfo.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoVertexShape.h>

#include "geometry/inventor_shape_check.hpp"
#include "geometry/mesh_readers.hpp"
#include "geometry/scene_include.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/geometry/mesh_loader.hpp"

namespace graspkit {
namespace {

using detail::checkShape;
using detail::pruneAppearance;
using detail::ShapeVerdict;

// Coin keeps global parser state and its error handlers are process-wide, so one file is read
// at a time. Loads are short (milliseconds) and usually happen once per model.
std::mutex coin_mutex;

// Messages Coin posts while a file is being read; null when no read is in progress.
std::vector<std::string>* coin_messages = nullptr;

// Texture images are never used (the traversal skips textures) and Coin is built without an
// image library here, so its complaints about them are noise.
bool isAboutTextureImages(const std::string& message) {
  return message.find("texture file") != std::string::npos ||
         message.find("SbImage::readFile") != std::string::npos;
}

void onCoinMessage(const SoError* error, void* /*data*/) {
  std::string message = error->getDebugString().getString();
  if (isAboutTextureImages(message)) return;
  if (coin_messages != nullptr) {
    coin_messages->push_back(std::move(message));
  } else {
    warn(WarningKind::Geometry, detail::locationIn("Coin3D"), message);
  }
}

// Routes Coin's messages into `messages` for as long as it lives (under coin_mutex).
class CoinMessageCapture {
 public:
  explicit CoinMessageCapture(std::vector<std::string>& messages) { coin_messages = &messages; }
  ~CoinMessageCapture() { coin_messages = nullptr; }
  CoinMessageCapture(const CoinMessageCapture&) = delete;
  CoinMessageCapture& operator=(const CoinMessageCapture&) = delete;
};

void installCoinHandlers() {
  SoError::setHandlerCallback(onCoinMessage, nullptr);
  SoReadError::setHandlerCallback(onCoinMessage, nullptr);
  SoDebugError::setHandlerCallback(onCoinMessage, nullptr);
}

// A world-space corner as the bit patterns of its float coordinates: equality is exact, and
// -0 and +0 (the same point) are made the same by adding +0.
using CornerKey = std::array<std::uint32_t, 3>;

CornerKey cornerKey(const SbVec3f& p) {
  return {std::bit_cast<std::uint32_t>(p[0] + 0.0f), std::bit_cast<std::uint32_t>(p[1] + 0.0f),
          std::bit_cast<std::uint32_t>(p[2] + 0.0f)};
}

// Merges bit-identical corners, which is how shared corners arrive from Coin (the same float
// through the same matrix). An open-addressing table over flat arrays keeps it free of
// per-vertex allocations.
class VertexWelder {
 public:
  std::uint32_t add(const CornerKey& key) {
    if (2 * (keys_.size() + 1) > slots_.size()) grow();
    std::size_t slot = hash(key) & (slots_.size() - 1);
    while (slots_[slot] != kEmpty) {
      if (keys_[slots_[slot]] == key) return slots_[slot];
      slot = (slot + 1) & (slots_.size() - 1);
    }
    slots_[slot] = static_cast<std::uint32_t>(keys_.size());
    keys_.push_back(key);
    return slots_[slot];
  }

  std::vector<Vector3> vertices() const {
    std::vector<Vector3> out;
    out.reserve(keys_.size());
    for (const CornerKey& key : keys_) {
      out.emplace_back(std::bit_cast<float>(key[0]), std::bit_cast<float>(key[1]),
                       std::bit_cast<float>(key[2]));
    }
    return out;
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  static std::size_t hash(const CornerKey& key) {
    std::uint64_t h = key[0];
    h = h * 0x9e3779b97f4a7c15ull ^ key[1];
    h = h * 0x9e3779b97f4a7c15ull ^ key[2];
    h *= 0x9e3779b97f4a7c15ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }

  void grow() {
    slots_.assign(std::max<std::size_t>(1024, 2 * slots_.size()), kEmpty);
    for (std::uint32_t i = 0; i < keys_.size(); ++i) {
      std::size_t slot = hash(keys_[i]) & (slots_.size() - 1);
      while (slots_[slot] != kEmpty) slot = (slot + 1) & (slots_.size() - 1);
      slots_[slot] = i;
    }
  }

  std::vector<CornerKey> keys_;
  std::vector<std::uint32_t> slots_;
};

// A scene may multiply its shapes (Array, USE, long Text3, a dense Extrusion) far beyond what
// its text size suggests; past this many triangles the load stops with an error, so memory and
// time stay bounded. GraspIt!'s largest models hold about 100,000.
constexpr std::size_t kMaxTriangles = 10'000'000;

struct TriangleCollector {
  VertexWelder welder;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Colour> colours;          // one per triangle: the diffuse colour in effect
  const SoNode* colourShape = nullptr;  // the shape `colour` was read for
  Colour colour;
  bool non_finite = false;
  bool too_many = false;
};

double determinant3x3(const SbMatrix& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

void onTriangle(void* data, SoCallbackAction* action, const SoPrimitiveVertex* v1,
                const SoPrimitiveVertex* v2, const SoPrimitiveVertex* v3) {
  auto& collector = *static_cast<TriangleCollector*>(data);
  if (collector.triangles.size() >= kMaxTriangles) {
    collector.too_many = true;
    return;
  }
  const SbMatrix& model = action->getModelMatrix();
  std::array<CornerKey, 3> corners;
  const SoPrimitiveVertex* sources[3] = {v1, v2, v3};
  for (int i = 0; i < 3; ++i) {
    SbVec3f world;
    model.multVecMatrix(sources[i]->getPoint(), world);
    if (!std::isfinite(world[0]) || !std::isfinite(world[1]) || !std::isfinite(world[2])) {
      collector.non_finite = true;
      return;
    }
    corners[i] = cornerKey(world);
  }
  // Two coincident corners make a triangle with no area that bounds nothing. GraspIt! leaves
  // these out too: its triangle counts for glass.iv and Robonaut are Coin's minus exactly these.
  if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) return;
  std::array<std::uint32_t, 3> triangle;
  for (int i = 0; i < 3; ++i) triangle[i] = collector.welder.add(corners[i]);
  // A mirroring transform turns Coin's counter-clockwise shapes inside out; undo that so the
  // mesh keeps outward winding and a positive volume.
  if (determinant3x3(model) < 0) std::swap(triangle[1], triangle[2]);
  collector.triangles.push_back(triangle);
  // Material bindings are pruned, so one diffuse colour holds for a whole shape: read it once.
  if (action->getCurPathTail() != collector.colourShape) {
    collector.colourShape = action->getCurPathTail();
    SbColor ambient, diffuse, specular, emission;
    float shininess = 0.0f, transparency = 0.0f;
    action->getMaterial(ambient, diffuse, specular, emission, shininess, transparency, 0);
    collector.colour = {diffuse[0], diffuse[1], diffuse[2]};
  }
  collector.colours.push_back(collector.colour);
}

// Coin's messages end with "Occurred at line N in <file>"; the line goes into the error's
// location and the rest of the message is kept.
void appendCoinMessage(const std::string& message, std::string& text, int& line) {
  std::string_view view = message;
  if (const std::size_t at = view.find("Occurred at line"); at != std::string_view::npos) {
    if (line == 0) {
      std::string_view number = view.substr(at + 16);
      number.remove_prefix(std::min(number.find_first_not_of(' '), number.size()));
      std::from_chars(number.data(), number.data() + number.size(), line);
    }
    view = view.substr(0, at);
  }
  while (!view.empty() && std::isspace(static_cast<unsigned char>(view.back()))) {
    view.remove_suffix(1);
  }
  if (!text.empty()) text += "; ";
  text += view;
}

SourceLocation coinLocation(const std::string& file, const std::vector<std::string>& messages,
                            std::string& text) {
  int line = 0;
  for (const std::string& message : messages) appendCoinMessage(message, text, line);
  return detail::locationIn(file, line);
}

// Coin's parser recurses once per nesting level and its traversal once per graph level, and a
// USE inside its own DEF makes a cycle; these bounds keep both within any thread's stack and
// a scene that multiplies itself through USE within a bounded time. GraspIt!'s models nest
// about ten levels deep and visit a few thousand nodes.
constexpr int kMaxNesting = 1000;
constexpr std::int64_t kMaxNodeVisits = 1'000'000;

// ASCII only, without the locale lookups of <cctype>: this runs on every byte of large files.
bool isWordStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
bool isPlain(char c) {
  return isDigit(c) || c == ' ' || c == '.' || c == ',' || c == '-' || c == '+' || c == '\t' ||
         c == '\r';
}

// Node types Coin may build from a file we read, by their name without the "So", "SoVRML" or
// "VRML" prefix Coin also accepts: the grouping, transform, property and shape nodes of
// Inventor 2.1, VRML 1.0 and VRML97, and harmless viewer nodes. Deny by default: any other type
// (File, Inline and WWWInline, which read other files; Font and FontStyle, whose names Coin may
// open as font files; Script, AudioClip, MovieTexture; types a PROTO or a `fields` list declares)
// is refused before Coin sees the text.
bool isAllowedNodeType(std::string_view type) {
  static constexpr std::string_view kAllowed[] = {
      // Grouping
      "Separator", "Group", "Switch", "TransformSeparator", "Annotation", "LevelOfDetail", "LOD",
      "Transform", "Collision", "Billboard", "Anchor", "Array", "MultipleCopy", "Selection",
      // Transforms
      "Translation", "Rotation", "RotationXYZ", "Scale", "MatrixTransform", "ResetTransform",
      "Units", "AntiSquish", "Texture2Transform", "TextureTransform",
      // Properties
      "Material", "BaseColor", "PackedColor", "MaterialBinding", "Normal", "NormalBinding",
      "Coordinate3", "Coordinate4", "Coordinate", "VertexProperty", "ShapeHints", "Complexity",
      "DrawStyle", "LightModel", "Texture2", "ImageTexture", "PixelTexture", "TextureCoordinate2",
      "TextureCoordinate", "TextureCoordinateBinding", "TextureCoordinateDefault", "Color",
      "Appearance", "Info", "WorldInfo", "Label", "EventCallback", "PickStyle", "Environment",
      "Fog",
      // Shapes
      "Cube", "Cone", "Cylinder", "Sphere", "Box", "FaceSet", "IndexedFaceSet", "TriangleStripSet",
      "IndexedTriangleStripSet", "QuadMesh", "IndexedLineSet", "LineSet", "PointSet",
      "IndexedPointSet", "Shape", "ElevationGrid", "Extrusion", "Text2", "Text3", "AsciiText",
      "Text",
      // Cameras, lights, sensors and interpolators (ignored, harmless)
      "PerspectiveCamera", "OrthographicCamera", "Viewpoint", "NavigationInfo", "Background",
      "DirectionalLight", "PointLight", "SpotLight", "TimeSensor", "TouchSensor", "ProximitySensor",
      "VisibilitySensor", "PlaneSensor", "CylinderSensor", "SphereSensor", "PositionInterpolator",
      "OrientationInterpolator", "ScalarInterpolator", "ColorInterpolator",
      "CoordinateInterpolator", "NormalInterpolator"};
  return std::find(std::begin(kAllowed), std::end(kAllowed), type) != std::end(kAllowed);
}

bool isUpper(char c) {
  return c >= 'A' && c <= 'Z';
}

// "SoVRMLInline", "VRMLInline" and "SoInline" all name Coin's Inline.
std::string_view withoutCoinPrefix(std::string_view type) {
  for (std::string_view prefix : {"SoVRML", "VRML", "So"}) {
    if (type.size() > prefix.size() && type.starts_with(prefix) && isUpper(type[prefix.size()]))
      return type.substr(prefix.size());
  }
  return type;
}

// Fields whose strings name files Coin would open while it parses (texture images, anchors,
// backgrounds). Textures are never used, so their names are blanked rather than refused.
bool namesFiles(std::string_view field) {
  static constexpr std::string_view kFields[] = {"filename", "url",     "backUrl",  "bottomUrl",
                                                 "frontUrl", "leftUrl", "rightUrl", "topUrl"};
  return std::find(std::begin(kFields), std::end(kFields), field) != std::end(kFields);
}

// Checks what Coin cannot be trusted with before it sees the text: binary files, nesting deep
// enough to overflow its recursive parser, node types outside isAllowedNodeType() (File and
// Inline above all, which make Coin read files this check never sees), and file names in
// fields, which are blanked. The text is tokenised as Coin does: blanks include form feeds and
// commas, comments run to the end of the line, strings are skipped whole.
class SceneTextCheck {
 public:
  SceneTextCheck(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  // The text Coin may read: the file's own, or a copy with file names blanked and each File node
  // replaced by a placeholder group (see includes()).
  std::string_view run() {
    checkHeader();
    while (pos_ < text_.size()) step();
    replaceIncludes();
    return edited_ ? std::string_view(*edited_) : text_;
  }

  // The File nodes found, in order. In the text Coin reads, each is a Group holding one Info node
  // whose string is the include's marker: the reader puts the included file's nodes there.
  const std::vector<detail::SceneInclude>& includes() const { return includes_; }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(detail::locationIn(file_, line_), message);
  }

  void checkHeader() {
    const std::string_view first_line = text_.substr(0, text_.find('\n'));
    if (!first_line.starts_with("#Inventor") && !first_line.starts_with("#VRML")) {
      fail("not an Inventor or VRML file: the first line must start with #Inventor or #VRML");
    }
    if (first_line.find("binary") != std::string_view::npos) {
      fail("binary Inventor files are not supported; convert the file to ASCII");
    }
  }

  static bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == ',';
  }

  void step() {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (c == '#') {
      pos_ = std::min(text_.find('\n', pos_), text_.size());
    } else if (c == '"') {
      skipString();
    } else if (c == '{' || c == '[') {
      if (++depth_ > kMaxNesting) fail(fmt::format("nesting deeper than {} levels", kMaxNesting));
      ++pos_;
    } else if (c == '}' || c == ']') {
      depth_ = std::max(0, depth_ - 1);
      ++pos_;
    } else if (isWordStart(c)) {
      checkWord();
    } else {
      // Numbers, blanks and separators: the bulk of a mesh file, skipped in a tight loop.
      do {
        ++pos_;
      } while (pos_ < text_.size() && isPlain(text_[pos_]));
    }
  }

  void skipString() {
    for (++pos_; pos_ < text_.size() && text_[pos_] != '"'; ++pos_) {
      if (text_[pos_] == '\\') ++pos_;
      if (pos_ < text_.size() && text_[pos_] == '\n') ++line_;
    }
    ++pos_;
  }

  // The position of the next character that is neither blank nor comment, from `at`; lines are
  // not counted (the caller does not move there).
  std::size_t nextToken(std::size_t at) const {
    while (at < text_.size()) {
      if (isBlank(text_[at])) {
        ++at;
      } else if (text_[at] == '#') {
        at = std::min(text_.find('\n', at), text_.size());
      } else {
        break;
      }
    }
    return at;
  }

  void checkWord() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (isWordStart(text_[pos_]) || isDigit(text_[pos_]))) ++pos_;
    const std::string_view word = text_.substr(start, pos_ - start);
    if (word == "EXTERNPROTO") fail("EXTERNPROTO, which reads other files, is not supported");
    const std::size_t next = nextToken(pos_);
    if (next < text_.size() && text_[next] == '{' && withoutCoinPrefix(word) == "File") {
      recordInclude(start, next);
    } else if (next < text_.size() && text_[next] == '{') {
      checkNodeType(word);
    } else if (namesFiles(word)) {
      blankStrings(next);
    }
  }

  // A File node, `File { name "part.iv" }`, from its type word at `start` to its closing brace:
  // recorded, and skipped (run() replaces it).
  void recordInclude(std::size_t start, std::size_t brace) {
    std::size_t at = nextToken(brace + 1);
    const std::string_view field = text_.substr(at, 4);
    at = nextToken(at + 4);
    if (field != "name" || at >= text_.size() || text_[at] == '}')
      fail("a File node holds one field: name \"file\"");
    std::string name;
    if (text_[at] == '"') {
      for (++at; at < text_.size() && text_[at] != '"'; ++at) {
        if (text_[at] == '\\' && at + 1 < text_.size()) ++at;
        name += text_[at];
      }
      at = nextToken(at + 1);
    } else {
      // Coin reads an unquoted string as one word, up to white space (GraspIt!'s ARMAR hand
      // writes `File { name armar/hands/palm1_r.iv }`).
      for (; at < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at])) &&
             text_[at] != '}';
           ++at)
        name += text_[at];
      at = nextToken(at);
    }
    if (at >= text_.size() || text_[at] != '}') fail("a File node holds one field: name \"file\"");
    static std::atomic<std::uint64_t> counter{0};
    includes_.push_back({name, line_, fmt::format("graspkit-include-{}", counter++)});
    include_spans_.emplace_back(start, at + 1);
    line_ += static_cast<int>(std::count(text_.begin() + pos_, text_.begin() + at + 1, '\n'));
    pos_ = at + 1;
  }

  // Each File node becomes `Group { Info { string "<marker>" } }` and the line breaks it held,
  // so that Coin's line numbers stay those of the file.
  void replaceIncludes() {
    if (includes_.empty()) return;
    if (!edited_) edited_.emplace(text_);
    for (std::size_t k = includes_.size(); k-- > 0;) {
      const auto [begin, end] = include_spans_[k];
      std::string placeholder =
          fmt::format("Group {{ Info {{ string \"{}\" }} }}", includes_[k].marker);
      placeholder.append(std::count(text_.begin() + begin, text_.begin() + end, '\n'), '\n');
      edited_->replace(begin, end - begin, placeholder);
    }
  }

  void checkNodeType(std::string_view word) const {
    const std::string_view type = withoutCoinPrefix(word);
    if (type == "Inline" || type == "WWWInline") {
      fail(fmt::format("{} nodes, which read other files, are not supported", word));
    }
    if (!isAllowedNodeType(type)) {
      fail(
          fmt::format("node type '{}' is not supported (graspkit reads the geometry, grouping, "
                      "transform and property nodes of Inventor and VRML)",
                      word));
    }
  }

  // Empties the string at `at`, or each string of the list that starts there, in the copy.
  void blankStrings(std::size_t at) {
    const bool list = at < text_.size() && text_[at] == '[';
    if (list) at = nextToken(at + 1);
    while (at < text_.size() && text_[at] == '"') {
      if (!edited_) edited_.emplace(text_);
      std::size_t end = at + 1;
      for (; end < text_.size() && text_[end] != '"'; ++end) {
        if (text_[end] == '\\') ++end;
      }
      // Keep the line breaks, so that Coin's line numbers stay those of the file.
      for (std::size_t i = at + 1; i < end && i < text_.size(); ++i)
        if ((*edited_)[i] != '\n') (*edited_)[i] = ' ';
      if (end < text_.size()) {
        (*edited_)[at + 1] = '"';  // "" followed by blanks
        if (end > at + 1) (*edited_)[end] = ' ';
      }
      if (!list) return;
      at = nextToken(end + 1);
    }
  }

  std::string_view text_;
  const std::string& file_;
  std::optional<std::string> edited_;
  std::vector<detail::SceneInclude> includes_;
  std::vector<std::pair<std::size_t, std::size_t>> include_spans_;  // [type word, closing brace]
  std::size_t pos_ = 0;
  int line_ = 1;
  int depth_ = 0;
};

// Parses the scene; Coin's diagnostics (with their line) become the error on failure.
SoSeparator* readScene(std::string_view text, const std::string& file,
                       const std::vector<std::string>& messages) {
  SoInput input;
  input.setBuffer(text.data(), text.size());
  SoSeparator* root = SoDB::readAll(&input);
  if (root == nullptr) {
    std::string reason;
    const SourceLocation where = coinLocation(file, messages, reason);
    throw Error(where,
                "cannot parse the scene: " + (reason.empty() ? "Coin gave no reason" : reason));
  }
  return root;
}

// State for the pre/post callbacks that guard Coin's traversal.
struct TraversalGuard {
  const TriangleCollector* collector = nullptr;
  std::int64_t visits = 0;
  int depth = 0;
  std::string problem;  // set when the traversal was aborted
};

// Without normals in the state Coin generates smooth ones for every Inventor vertex shape, which
// costs as much as tessellating; one overall normal stands in, since only positions are kept.
void skipNormalGeneration(SoCallbackAction& action, SoNode& shape) {
  if (!shape.isOfType(SoVertexShape::getClassTypeId())) return;
  static const SbVec3f kAnyNormal(0.0f, 0.0f, 1.0f);
  SoNormalElement::set(action.getState(), &shape, 1, &kAnyNormal, TRUE);
  SoNormalBindingElement::set(action.getState(), &shape, SoNormalBindingElement::OVERALL);
}

SoCallbackAction::Response beforeNode(void* data, SoCallbackAction* action, const SoNode* node) {
  auto& guard = *static_cast<TraversalGuard*>(data);
  if (guard.collector->too_many) return SoCallbackAction::ABORT;
  if (++guard.visits > kMaxNodeVisits) {
    guard.problem = fmt::format("the scene graph expands to more than {} nodes", kMaxNodeVisits);
    return SoCallbackAction::ABORT;
  }
  if (++guard.depth > kMaxNesting) {
    constexpr const char* kTooDeep =
        "the scene graph is deeper than {} levels; a USE inside its own DEF makes a cycle";
    guard.problem = fmt::format(kTooDeep, kMaxNesting);
    return SoCallbackAction::ABORT;
  }
  // The scene is ours and discarded after loading, so the checks may edit it.
  SoNode& editable = const_cast<SoNode&>(*node);
  if (pruneAppearance(editable)) return SoCallbackAction::PRUNE;
  if (!node->isOfType(SoShape::getClassTypeId())) return SoCallbackAction::CONTINUE;
  const ShapeVerdict verdict = checkShape(*action, editable);
  switch (verdict.kind) {
    case ShapeVerdict::Traverse:
      skipNormalGeneration(*action, editable);
      return SoCallbackAction::CONTINUE;
    case ShapeVerdict::Skip:
      return SoCallbackAction::PRUNE;
    case ShapeVerdict::Reject:
      break;
  }
  guard.problem = verdict.problem;
  return SoCallbackAction::ABORT;
}

SoCallbackAction::Response afterNode(void* data, SoCallbackAction* /*action*/,
                                     const SoNode* /*node*/) {
  --static_cast<TraversalGuard*>(data)->depth;
  return SoCallbackAction::CONTINUE;
}

// Holds a reference to a scene for as long as it is traversed; the last unref frees it.
class SceneReference {
 public:
  explicit SceneReference(SoSeparator* root) : root_(root) { root_->ref(); }
  ~SceneReference() { root_->unref(); }
  SceneReference(const SceneReference&) = delete;
  SceneReference& operator=(const SceneReference&) = delete;
  SoSeparator* get() const { return root_; }

 private:
  SoSeparator* root_;
};

TriangleCollector collectTriangles(SoSeparator* root, const std::string& file) {
  const SceneReference scene(root);
  TriangleCollector collector;
  TraversalGuard guard;
  guard.collector = &collector;
  SoCallbackAction action;
  action.addPreCallback(SoNode::getClassTypeId(), beforeNode, &guard);
  action.addPostCallback(SoNode::getClassTypeId(), afterNode, &guard);
  action.addTriangleCallback(SoShape::getClassTypeId(), onTriangle, &collector);
  action.apply(scene.get());
  if (!guard.problem.empty()) throw Error(detail::locationIn(file), guard.problem);
  if (collector.too_many) {
    throw Error(detail::locationIn(file),
                fmt::format("the scene expands to more than {} triangles", kMaxTriangles));
  }
  return collector;
}

}  // namespace

void initInventorReader() {
  static std::once_flag once;
  std::call_once(once, [] {
    SoDB::init();
    installCoinHandlers();
  });
}

namespace detail {
namespace {

// An included scene's nodes go where its File node was: into the placeholder group (no separator,
// as Coin's SoFile adds the file's top-level nodes as its own children, so state carries on).
void splice(SoSeparator& scene, const std::string& marker, SoSeparator& included) {
  SoSearchAction search;
  search.setType(SoInfo::getClassTypeId());
  search.setInterest(SoSearchAction::ALL);
  search.setSearchingAll(TRUE);
  search.apply(&scene);
  // Collected first: removing a child makes Coin shorten every path through it.
  std::vector<std::pair<SoGroup*, SoNode*>> places;
  const SoPathList& paths = search.getPaths();
  for (int i = 0; i < paths.getLength(); ++i) {
    const SoPath& path = *paths[i];
    SoNode* tail = path.getTail();
    if (path.getLength() < 2 || !tail->isOfType(SoInfo::getClassTypeId())) continue;
    if (marker != static_cast<SoInfo*>(tail)->string.getValue().getString()) continue;
    auto* group = static_cast<SoGroup*>(path.getNodeFromTail(1));
    const bool seen = std::any_of(places.begin(), places.end(),
                                  [&](const auto& place) { return place.first == group; });
    if (!seen) places.emplace_back(group, tail);  // once per group, however often it is USEd
  }
  for (const auto& [group, info] : places) {
    group->removeChild(info);
    for (int c = 0; c < included.getNumChildren(); ++c) group->addChild(included.getChild(c));
  }
}

// What the files of one scene share: the model root, the chain of including files (innermost
// last, resolved), and the text read so far.
struct SceneFiles {
  std::filesystem::path root;
  std::vector<std::filesystem::path> chain;
  std::size_t bytes = 0;
};

// Parses `path` and, recursively, the files its File nodes name (see scene_include.hpp). The
// result carries one reference, which the caller owns.
SoSeparator* readSceneFile(const std::filesystem::path& path, SceneFiles& files,
                           std::vector<std::string>& messages) {
  const std::string file = path.string();
  const std::string text = readInputFile(path);
  files.bytes += text.size();
  if (files.bytes > kMaxIncludedBytes)
    throw Error(locationIn(file), fmt::format("the scene's files hold more than {} bytes of text "
                                              "in all",
                                              kMaxIncludedBytes));
  SceneTextCheck check(text, file);
  const std::string_view checked = check.run();
  SoSeparator* scene = readScene(checked, file, messages);
  scene->ref();
  try {
    for (const SceneInclude& include : check.includes()) {
      std::vector<std::filesystem::path> folders;
      folders.push_back(path.parent_path());
      for (auto outer = files.chain.rbegin(); outer != files.chain.rend(); ++outer)
        if (std::find(folders.begin(), folders.end(), outer->parent_path()) == folders.end())
          folders.push_back(outer->parent_path());
      const auto found = resolveInclude(include.name, folders, files.root, file, include.line);
      if (!found) {
        std::string searched;
        for (const auto& folder : folders)
          searched += (searched.empty() ? "" : ", ") + folder.string();
        warn(WarningKind::Geometry, locationIn(file, include.line),
             fmt::format("File node names '{}', which is in none of the folders searched ({}); "
                         "skipped, as Coin does",
                         include.name, searched));
        continue;
      }
      const std::filesystem::path real = std::filesystem::weakly_canonical(*found);
      if (std::find(files.chain.begin(), files.chain.end(), real) != files.chain.end())
        throw Error(locationIn(file, include.line),
                    fmt::format("File node includes '{}', which includes this file: a cycle",
                                include.name));
      if (static_cast<int>(files.chain.size()) > kMaxIncludeDepth)
        throw Error(locationIn(file, include.line),
                    fmt::format("File nodes nest deeper than {} files", kMaxIncludeDepth));
      files.chain.push_back(real);
      SoSeparator* included = readSceneFile(*found, files, messages);
      files.chain.pop_back();
      splice(*scene, include.marker, *included);
      included->unref();
    }
  } catch (...) {
    scene->unref();
    throw;
  }
  return scene;
}

}  // namespace

TriangleMesh readInventor(const std::filesystem::path& path) {
  initInventorReader();
  const std::string file = path.string();
  std::vector<std::string> messages;
  TriangleCollector collector;
  {
    std::lock_guard lock(coin_mutex);
    CoinMessageCapture capture(messages);
    SceneFiles files;
    files.root = std::filesystem::weakly_canonical(std::filesystem::absolute(path)).parent_path();
    files.chain.push_back(std::filesystem::weakly_canonical(std::filesystem::absolute(path)));
    SoSeparator* scene = readSceneFile(path, files, messages);
    const SceneReference hold(scene);
    scene->unrefNoDelete();  // the hold keeps it alive now
    collector = collectTriangles(scene, file);
  }
  const SourceLocation where = locationIn(file);
  if (collector.non_finite) throw Error(where, "a vertex has a non-finite coordinate");
  // Coin accepted the file; whatever it said along the way is worth a look, not a failure.
  for (const std::string& message : messages) {
    std::string text_only;
    const SourceLocation at = coinLocation(file, {message}, text_only);
    warn(WarningKind::Geometry, at, text_only);
  }
  TriangleMesh mesh;
  mesh.vertices = collector.welder.vertices();
  mesh.triangles = std::move(collector.triangles);
  // A scene without a material node shows Coin's default grey everywhere: no colours of its own.
  const bool coloured = std::any_of(collector.colours.begin(), collector.colours.end(),
                                    [](const Colour& c) { return !(c == Colour{}); });
  if (coloured) mesh.triangleColours = std::move(collector.colours);
  return mesh;
}

}  // namespace detail
}  // namespace graspkit
