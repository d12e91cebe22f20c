#include "graspkit/io/graspit/world_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include "graspkit/base/file_reference.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/base/version.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "io/common/export_text.hpp"
#include "io/common/xml.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

class WorldReader {
 public:
  WorldReader(const fs::path& file, const LoadOptions& options, ModelCache* cache)
      : file_(file), roots_(searchRoots(file, options)), options_(options), cache_(cache) {}

  World read() {
    xml::Document doc(file_);
    const XMLElement& root = doc.root();
    if (std::string_view(root.Name()) != "world") {
      throw Error(xml::at(file_, root), "the root element of a world file must be <world>");
    }
    xml::warnUnknownChildren(file_, root,
                             {"obstacle", "graspableBody", "robot", "connection", "camera"});
    World world;
    for (auto* e = root.FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string_view name = e->Name();
      if (name == "obstacle") readBody(*e, BodyKind::Obstacle, world);
      if (name == "graspableBody") readBody(*e, BodyKind::Graspable, world);
      if (name == "robot") readRobot(*e, world);
    }
    for (const XMLElement* e : xml::children(root, "connection")) readConnection(*e, world);
    if (const auto* e = xml::child(root, "camera")) readCamera(*e, world);
    return world;
  }

 private:
  // The search rule (world_file.hpp, loadWorldFile): an absolute name is itself; a name
  // starting with `./` or `../` (what graspkit writes) is first looked for beside this world
  // file; every other name, and such a name not found there, is looked up under each of roots_
  // in turn (--root, $GRASPKIT_ROOT, $GRASPIT, then this file's folder and each of its parents:
  // GraspIt!'s names are relative to its root, and `../shared/...` names relative to a root are
  // in use).
  fs::path resolve(const XMLElement& element) {
    const std::string name = xml::text(element);
    if (name.empty()) throw Error(xml::at(file_, element), "empty file name");
    // One place to look: the read gives the reason it fails (refused, missing, a loop).
    if (fs::path(name).is_absolute()) return name;
    if (isFileRelative(name)) {
      const fs::path path = fs::absolute(file_).parent_path() / name;
      if (inputFileFound(path)) return path;
    }
    std::optional<fs::path> refused;
    for (const fs::path& root : roots_) {
      if (inputFileFound(root / name)) return root / name;
      if (!refused && inputFileRefused(root / name)) refused = root / name;
    }
    // Found nowhere it may be read: the read of the first refused place gives the refusal.
    if (refused) return *refused;
    std::string tried;
    for (const fs::path& root : roots_) tried.append("\n  ").append(root.string());
    throw Error(
        xml::at(file_, element),
        fmt::format("'{}' not found; searched (set --root or GRASPKIT_ROOT):{}", name, tried));
  }

  Transform pose(const XMLElement& parent) {
    const auto* t = xml::child(parent, "transform");
    return t ? xml::transform(file_, *t) : Transform::Identity();
  }

  void readBody(const XMLElement& element, BodyKind kind, World& world) {
    if (xml::child(element, "body") && !xml::child(element, "filename")) {
      throw Error(xml::at(file_, element), "inline <body> definitions are not supported");
    }
    const XMLElement& filename = xml::requiredChild(file_, element, "filename");
    const fs::path path = resolve(filename);
    Body body;
    body.model = xml::locatedAt(file_, filename, [&] { return loadBodyFile(path, cache_); });
    if (kind == BodyKind::Graspable) warnIfInertiaFallback(*body.model, xml::at(file_, filename));
    body.kind = kind;
    body.filename = xml::text(filename);
    body.setPose(pose(element));
    world.addBody(std::move(body));
  }

  void readRobot(const XMLElement& element, World& world) {
    const XMLElement& filename = xml::requiredChild(file_, element, "filename");
    const fs::path path = resolve(filename);
    Robot robot(
        xml::locatedAt(file_, filename, [&] { return loadRobotFile(path, options_, cache_); }));
    if (const auto* values = xml::child(element, "dofValues")) readDofValues(*values, robot);
    robot.setPose(pose(element));  // GraspIt! applies the transform after the DOF values
    world.addRobot(std::move(robot), xml::text(filename));
  }

  // Rigid and compliant DOFs: one value. Breakaway DOFs: the value, then per coupled joint
  // `0`, or `1 <value>` for a joint that broke away at that DOF value.
  void readDofValues(const XMLElement& element, Robot& robot) {
    const std::string content = xml::text(element);
    const auto tokens = xml::tokens(content);
    std::size_t next = 0;
    auto take = [&](const char* what) {
      if (next >= tokens.size()) {
        throw Error(xml::at(file_, element),
                    fmt::format("too few values for robot '{}' ({} DOFs): ran out reading {}",
                                robot.name(), robot.dofCount(), what));
      }
      auto value = xml::toDouble(tokens[next]);
      if (!value) {
        throw Error(xml::at(file_, element),
                    fmt::format("'{}' is not a finite number", tokens[next]));
      }
      ++next;
      return *value;
    };
    const RobotModel& model = robot.model();
    std::vector<double> values(model.dofs.size());
    std::vector<std::pair<int, BreakawayState>> broken;
    for (std::size_t d = 0; d < model.dofs.size(); ++d) {
      values[d] = take("a DOF value");
      if (model.dofs[d].type != DofType::Breakaway) continue;
      for (int joint : model.dofs[d].joints) {
        const double flag = take("a breakaway flag");
        if (flag != 0.0 && flag != 1.0) {
          throw Error(xml::at(file_, element),
                      fmt::format("breakaway flag of DOF {} is {}, expected 0 or 1", d, flag));
        }
        if (flag == 1.0)
          broken.emplace_back(joint, BreakawayState{true, take("a breakaway value")});
      }
    }
    if (next != tokens.size()) {
      throw Error(xml::at(file_, element),
                  fmt::format("{} values given, robot '{}' ({} DOFs) takes {}", tokens.size(),
                              robot.name(), robot.dofCount(), next));
    }
    robot.setDofValues(values, LimitPolicy::Ignore);
    for (const auto& [joint, state] : broken) robot.setBreakaway(joint, state);
  }

  void readConnection(const XMLElement& element, World& world) {
    Connection connection;
    connection.parentRobot = xml::integer(file_, xml::requiredChild(file_, element, "parentRobot"));
    connection.parentChain = xml::integer(file_, xml::requiredChild(file_, element, "parentChain"));
    connection.childRobot = xml::integer(file_, xml::requiredChild(file_, element, "childRobot"));
    if (const auto* mount = xml::child(element, "mountFilename")) {
      connection.mountFilename = xml::text(*mount);
      const fs::path path = resolve(*mount);
      connection.mount = xml::locatedAt(file_, *mount, [&] { return loadBodyFile(path, cache_); });
    }
    connection.offset = pose(element);
    xml::locatedAt(file_, element, [&] {
      world.connect(std::move(connection));
      return 0;
    });
  }

  void readCamera(const XMLElement& element, World& world) {
    Camera camera;
    camera.position = xml::vector3(file_, xml::requiredChild(file_, element, "position"));
    // Passed straight to Coin by GraspIt!, so x y z w, unlike every other quaternion.
    const auto q = xml::numbers(file_, xml::requiredChild(file_, element, "orientation"), 4);
    // Kept as written (saving writes it back byte for byte), but it must name a rotation.
    xml::checkedQuaternion(file_, *xml::child(element, "orientation"), q[3], q[0], q[1], q[2]);
    camera.orientation = Quaternion(q[3], q[0], q[1], q[2]);
    camera.focalDistance = xml::optionalNumber(file_, element, "focalDistance", 0.0);
    world.setCamera(camera);
  }

  fs::path file_;
  std::vector<fs::path> roots_;
  const LoadOptions& options_;
  ModelCache* cache_;
};

// Shortest text that reads back to the same double, with an explicit sign as GraspIt! writes.
std::string signedNumber(double value) {
  if (value == 0.0) value = 0.0;  // no "-0"
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  return value >= 0 ? "+" + text : text;
}

// The name a world saved as `world_file` gives a model file, so that the world loads again from
// any working folder with no --root (world_file.hpp, base/file_reference.hpp):
// - the name it was loaded by (`written`, GraspIt!'s root-relative `models/objects/mug.xml`),
//   when the saved world's folder or one of its parents holds that very file (a world saved
//   back into its own tree keeps GraspIt!'s names);
// - else the model's path relative to the saved world's folder, starting with `./` or `../`
//   (looked for beside the world file before any root), or its absolute path when the two share
//   no folder below the file system's root.
std::string modelName(const std::string& written, const fs::path& model_file,
                      const fs::path& world_file) {
  if (model_file.empty()) return written;  // nothing to say better (a body made in memory)
  const fs::path folder = fs::absolute(world_file).parent_path();
  std::error_code ec;
  if (!written.empty() && !fs::path(written).is_absolute() && !isFileRelative(written)) {
    for (fs::path dir = folder;; dir = dir.parent_path()) {
      if (fs::exists(dir / written, ec)) {
        if (fs::equivalent(dir / written, model_file, ec)) return written;
        break;  // the reload would find another file first
      }
      if (!dir.has_parent_path() || dir.parent_path() == dir) break;
    }
  }
  const std::string reference = fileReference(model_file, folder);
  return fs::path(reference).is_absolute() || isFileRelative(reference) ? reference
                                                                        : "./" + reference;
}

void writeTransform(std::ostream& out, const Transform& transform, const char* indent) {
  out << indent << "<transform>\n"
      << indent << "    <fullTransform>" << formatFullTransform(transform) << "</fullTransform>\n"
      << indent << "</transform>\n";
}

// Which engine and which robot-type plugins produced the file. A comment before the root
// element, so GraspIt! (which refuses unknown tags inside <world>) still reads the file.
std::string provenanceComment(const World& world) {
  std::set<std::string> types;
  for (int r = 0; r < world.robotCount(); ++r) {
    const RobotModel& model = world.robot(r).model();
    types.insert(model.type + " (" +
                 (model.typeProvider.empty() ? "built in" : model.typeProvider) + ")");
  }
  std::string text = fmt::format("<!-- saved by graspkit {}", engineVersion());
  if (!types.empty()) text += fmt::format("; robot types: {}", fmt::join(types, ", "));
  return text + " -->\n";
}

std::string worldText(const World& world, const fs::path& file) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" ?>\n" << provenanceComment(world) << "<world>\n";
  for (const Body& body : world.bodies()) {
    const char* tag = body.kind == BodyKind::Graspable ? "graspableBody" : "obstacle";
    const std::string name =
        modelName(body.filename.generic_string(), body.model ? body.model->file : fs::path(), file);
    out << "    <" << tag << ">\n        <filename>" << io::xmlEscaped(name) << "</filename>\n";
    writeTransform(out, body.pose, "        ");
    out << "    </" << tag << ">\n";
  }
  for (int r = 0; r < world.robotCount(); ++r) {
    const WorldRobot& entry = world.worldRobot(r);
    const std::string name =
        modelName(entry.filename.generic_string(), entry.robot.model().file, file);
    out << "    <robot>\n        <filename>" << io::xmlEscaped(name) << "</filename>\n"
        << "        <dofValues>" << formatDofValues(entry.robot) << "</dofValues>\n";
    writeTransform(out, entry.robot.pose(), "        ");
    out << "    </robot>\n";
  }
  for (const Connection& c : world.connections()) {
    out << "    <connection>\n"
        << "        <parentRobot>" << c.parentRobot << "</parentRobot>\n"
        << "        <parentChain>" << c.parentChain << "</parentChain>\n"
        << "        <childRobot>" << c.childRobot << "</childRobot>\n";
    if (!c.mountFilename.empty() || c.mount) {
      const std::string name =
          modelName(c.mountFilename, c.mount ? c.mount->file : fs::path(), file);
      out << "        <mountFilename>" << io::xmlEscaped(name) << "</mountFilename>\n";
    }
    writeTransform(out, c.offset, "        ");
    out << "    </connection>\n";
  }
  if (const auto& camera = world.camera()) {
    const Quaternion& q = camera->orientation;
    out << "    <camera>\n        <position>" << signedNumber(camera->position.x()) << " "
        << signedNumber(camera->position.y()) << " " << signedNumber(camera->position.z())
        << "</position>\n        <orientation>" << signedNumber(q.x()) << " " << signedNumber(q.y())
        << " " << signedNumber(q.z()) << " " << signedNumber(q.w()) << "</orientation>\n"
        << "        <focalDistance>" << signedNumber(camera->focalDistance)
        << "</focalDistance>\n    </camera>\n";
  }
  out << "</world>\n";
  return out.str();
}

std::string rootName(const fs::path& file) {
  xml::Document doc(file);
  return doc.root().Name();
}

}  // namespace

std::vector<fs::path> searchRoots(const fs::path& world_file, const LoadOptions& options) {
  std::vector<fs::path> roots;
  std::vector<fs::path> seen;  // each folder once, however it was spelled (models, ./models/)
  auto add = [&](const fs::path& folder) {
    std::error_code ec;
    fs::path key = fs::absolute(folder, ec).lexically_normal();
    if (key.has_relative_path() && !key.has_filename()) key = key.parent_path();  // trailing /
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) return;
    seen.push_back(key);
    roots.push_back(folder);
  };
  for (const fs::path& root : options.roots) add(root);
  if (options.useEnvironment) {
    for (const char* variable : {"GRASPKIT_ROOT", "GRASPIT"}) {
      if (const char* value = std::getenv(variable); value && *value) add(value);
    }
  }
  fs::path dir = fs::absolute(world_file).parent_path();
  while (true) {
    add(dir);
    if (!dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return roots;
}

World loadWorldFile(const fs::path& file, const LoadOptions& options, ModelCache* cache) {
  ModelCache local;  // files named twice in one world are read once, even without a cache
  return WorldReader(file, options, cache ? cache : &local).read();
}

World loadAnyFile(const fs::path& file, const LoadOptions& options, ModelCache* cache) {
  const std::string root = isMeshFile(file) ? "" : rootName(file);
  if (root == "world") return loadWorldFile(file, options, cache);
  World world;
  if (root == "robot" || root == "mujoco") {
    world.addRobot(Robot(loadRobotFile(file, options, cache)), file);
  } else {
    Body body;
    body.model = loadBodyFile(file, cache);
    warnIfInertiaFallback(*body.model, SourceLocation{file.string()});
    body.kind = BodyKind::Graspable;
    body.filename = file;
    body.setPose(Transform::Identity());
    world.addBody(std::move(body));
  }
  return world;
}

namespace {

// The quaternion a save writes for `rotation`. q -> R -> q is not exact in floating point, so
// writing q's shortest round-trip digits drifts in the last places on every save -> load ->
// save. Components are rounded to 14 decimals (rotation error < 1e-13), which absorbs that
// drift, and the rounding is repeated through the load path (makeTransform) until reading the
// text back gives the same text again.
Quaternion savedRotation(const Matrix3& rotation) {
  auto rounded = [](Quaternion q) {
    q.normalize();
    for (int i = 0; i < 4; ++i) q.coeffs()[i] = std::round(q.coeffs()[i] * 1e14) / 1e14;
    return q;
  };
  Quaternion q = rounded(Quaternion(rotation));
  for (int i = 0; i < 8; ++i) {
    const Quaternion next = rounded(Quaternion(makeTransform(Vector3::Zero(), q).linear()));
    if (next.coeffs() == q.coeffs()) break;
    q = next;
  }
  return q;
}

}  // namespace

std::string formatFullTransform(const Transform& transform) {
  const Quaternion q = savedRotation(transform.linear());
  const Vector3& t = transform.translation();
  return fmt::format("({} {} {} {})[{} {} {}]", signedNumber(q.w()), signedNumber(q.x()),
                     signedNumber(q.y()), signedNumber(q.z()), signedNumber(t.x()),
                     signedNumber(t.y()), signedNumber(t.z()));
}

std::string formatDofValues(const Robot& robot) {
  std::string out;
  const RobotModel& model = robot.model();
  for (std::size_t d = 0; d < model.dofs.size(); ++d) {
    if (!out.empty()) out += ' ';
    out += signedNumber(robot.dofValues()[d]);
    if (model.dofs[d].type != DofType::Breakaway) continue;
    for (int joint : model.dofs[d].joints) {
      const BreakawayState& state = robot.breakaway()[joint];
      out += state.engaged ? " 1 " + signedNumber(state.value) : " 0";
    }
  }
  return out;
}

void saveWorldFile(const World& world, const fs::path& file) {
  writeFileAtomically(file, worldText(world, file));
}

}  // namespace graspkit
