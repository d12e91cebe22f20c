// MJCF (MuJoCo's XML) robots as graspkit hands. The file is read in three steps:
//  1. Parse: <include> files are spliced in where they stand; <compiler> sets angle units,
//     mesh folders and the Euler sequence; <default> classes (nested, with `class` and
//     `childclass`) give each element its attributes; the <worldbody> tree becomes bodies with
//     their joints, collision geometry (meshes and primitives) and inertia.
//  2. Drive: each actuator is a DOF. A joint actuator drives its joint; a fixed-tendon actuator
//     drives the tendon's joints in the ratio of their coefficients; <equality><joint> couples
//     joints linearly (polycoef c0 + c1 q); <equality><connect> closes a loop, whose passive
//     joints are solved at samples of the DOF and follow it by the least-squares line through
//     them. Joints no actuator reaches are frozen at their reference; a model without actuators
//     makes every joint a DOF.
//  3. Build: bodies joined without moving joints form one link (the palm is everything fixed
//     to the world); each moving joint hung on the palm starts a chain, whose joint axes become
//     DH joints as for URDF (io/urdf/denavit_hartenberg_fit.hpp) and whose links keep their MJCF
//     body frames.
// Units: metres become millimetres, kilograms grams.

#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/base/input_file.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "geometry/convex_hull.hpp"
#include "geometry/primitive_meshes.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/collision/self_collision_setup.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "graspkit/math/units.hpp"
#include "graspkit/model/closing_direction.hpp"
#include "graspkit/model/eigengrasp.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/plugin/registry.hpp"
#include "io/common/link_mass.hpp"
#include "io/common/xml.hpp"
#include "io/urdf/denavit_hartenberg_fit.hpp"
#include "model/dof_ranges.hpp"

namespace graspkit {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

namespace {

// The path include cycles are judged by; one that cannot be resolved (a loop of symbolic links)
// stays as given, and reading it then names the reason.
fs::path canonicalOrAsGiven(const fs::path& file) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(file, ec);
  return ec ? file : canonical;
}

// Controller gains as for URDF hands (io/urdf/urdf_file.cpp): GraspIt!'s Barrett for revolute DOFs,
// graspkit's parallel_jaw for prismatic ones.
constexpr double kRevoluteKp = 1.0e11, kRevoluteKd = 1.0e7, kRevoluteEffort = 2.5e9;
constexpr double kPrismaticKp = 1.0e9, kPrismaticKd = 1.0e6, kPrismaticEffort = 1.0e8;
constexpr int kMaxIncludeDepth = 16;
constexpr std::size_t kMaxBodies = 4096;
constexpr std::size_t kMaxChainJoints = 4096;  // shared joints repeated
constexpr double kLoopSamples = 40;            // DOF samples a loop is solved at
constexpr double kLoopWarnGap = 0.5;           // mm: a fitted loop opening more than this warns
constexpr double kLoopSolveTolerance = 1e-6;   // mm

// An element and the file it was read from (an <include>d file has its own lines).
struct Source {
  const XMLElement* element = nullptr;
  const fs::path* file = nullptr;
  SourceLocation where() const { return xml::at(*file, *element); }
};

struct MjJoint {
  std::string name;
  Source source;
  int body = -1;
  bool slide = false;
  Vector3 pos = Vector3::Zero();  // mm, body frame
  Vector3 axis = Vector3::UnitZ();
  bool limited = false;
  double lo = 0.0, hi = 0.0;  // rad or mm
  double ref = 0.0;
  double damping = 0.0, frictionloss = 0.0;
};

struct MjBody {
  std::string name;
  Source source;
  int parent = -1;                          // -1: the world
  Transform local = Transform::Identity();  // in the parent's frame, mm
  std::vector<int> joints;
  std::vector<int> children;
  TriangleMesh mesh;  // collision geometry, body frame, mm
  std::string meshFile;
  bool hasInertial = false;
  double mass = 0.0;  // g
  Vector3 cog = Vector3::Zero();
  Matrix3 inertia = Matrix3::Zero();  // about the cog, body frame, g mm^2
  double geomMass = 0.0;              // g, from geoms when there is no <inertial>
};

// How a joint moves: value = ratio * DOF + offset (MJCF units: rad or m... here rad or mm).
struct Drive {
  int dof = -1;  // -1: not driven
  double ratio = 1.0;
  double offset = 0.0;
};

struct DofSpec {
  std::string name;
  Source source;
  double kp = 0.0;
  double effort = 0.0;  // N or N m, 0: not given
};

struct MeshAsset {
  fs::path file;
  Vector3 scale = Vector3::Ones();
  Vector3 refpos = Vector3::Zero();
  Quaternion refquat = Quaternion::Identity();
  Source source;
};

void appendMesh(TriangleMesh& to, TriangleMesh part, const Transform& placed) {
  transformMesh(part, Eigen::Affine3d(placed.matrix()));
  const auto offset = static_cast<std::uint32_t>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const auto& t : part.triangles)
    to.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

class MjcfReader {
 public:
  MjcfReader(const fs::path& file, const LoadOptions& options) : file_(file), options_(options) {}

  std::shared_ptr<const RobotModel> read() {
    const xml::Document& main = document(file_);
    if (std::string_view(main.root().Name()) != "mujoco")
      throw Error(xml::at(file_, main.root()), "the root element of an MJCF file must be <mujoco>");
    std::vector<Source> top;
    std::vector<fs::path> stack{canonicalOrAsGiven(file_)};
    expand(main.root(), main.file(), top, stack);
    for (const Source& s : top)
      if (name(s) == "compiler") readCompiler(s);
    for (const Source& s : top)
      if (name(s) == "default") readDefaults(s, "main", "");
    for (const Source& s : top)
      if (name(s) == "asset") readAssets(s);
    for (const Source& s : top)
      if (name(s) == "worldbody") readBodies(s, -1, "main");
    if (bodies_.empty())
      throw Error(xml::at(file_, main.root()), "the <worldbody> holds no body: no hand to load");
    for (const Source& s : top)
      if (name(s) == "tendon") readTendons(s);
    for (const Source& s : top)
      if (name(s) == "actuator") readActuators(s);
    drives_.assign(joints_.size(), Drive{});
    makeDofs();
    for (const Source& s : top)
      if (name(s) == "equality") readJointEqualities(s);
    for (const Source& s : top)
      if (name(s) == "equality") readConnects(s);
    for (const Source& s : top)
      if (name(s) == "contact") readExclusions(s);
    return build(main.root().Attribute("model"));
  }

 private:
  // --- Files, includes, attributes ----------------------------------------------------------

  const xml::Document& document(const fs::path& file) {
    documents_.push_back(std::make_unique<xml::Document>(file));
    return *documents_.back();
  }

  static std::string name(const Source& s) { return s.element->Name(); }

  // The children of `parent`, with each <include file> replaced by the children of the
  // included file's <mujoco> (MuJoCo reads include paths from the main file's folder).
  void expand(const XMLElement& parent, const fs::path& file, std::vector<Source>& out,
              std::vector<fs::path>& stack) {
    for (const XMLElement* e = parent.FirstChildElement(); e; e = e->NextSiblingElement()) {
      if (std::string_view(e->Name()) != "include") {
        out.push_back({e, &paths_.emplace_back(file)});
        continue;
      }
      const char* name = e->Attribute("file");
      if (!name) throw Error(xml::at(file, *e), "<include> needs a file attribute");
      const fs::path included = file_.parent_path() / name;
      const fs::path canonical = canonicalOrAsGiven(included);
      if (std::find(stack.begin(), stack.end(), canonical) != stack.end())
        throw Error(xml::at(file, *e), fmt::format("include cycle: '{}' includes itself", name));
      if (stack.size() >= kMaxIncludeDepth)
        throw Error(xml::at(file, *e), "includes nest deeper than 16 files");
      xml::locatedAt(file, *e, [&] {
        checkInputFile(included);
        return 0;
      });
      const xml::Document& doc = document(included);
      if (std::string_view(doc.root().Name()) != "mujoco")
        throw Error(xml::at(included, doc.root()),
                    "an included MJCF file's root element must be <mujoco>");
      stack.push_back(canonical);
      expand(doc.root(), doc.file(), out, stack);
      stack.pop_back();
    }
  }

  // The children of a source element, includes expanded.
  std::vector<Source> childrenOf(const Source& s) {
    std::vector<Source> out;
    std::vector<fs::path> stack{canonicalOrAsGiven(*s.file)};
    expand(*s.element, *s.file, out, stack);
    return out;
  }

  // An attribute from the element itself, else from its default class (and the classes above).
  std::optional<std::string> attribute(const Source& s, const std::string& cls,
                                       const char* attr) const {
    if (const char* own = s.element->Attribute(attr)) return std::string(own);
    const auto c = classes_.find(cls);
    if (c == classes_.end()) return std::nullopt;
    const auto tag = c->second.find(s.element->Name());
    if (tag == c->second.end()) return std::nullopt;
    const auto value = tag->second.find(attr);
    if (value == tag->second.end()) return std::nullopt;
    return value->second;
  }

  // The class an element takes: its own `class`, else the enclosing childclass.
  std::string classOf(const Source& s, const std::string& childclass) const {
    const char* own = s.element->Attribute("class");
    const std::string cls = own ? own : childclass;
    if (!classes_.count(cls))
      throw Error(s.where(), fmt::format("unknown default class '{}'", cls));
    return cls;
  }

  std::optional<std::vector<double>> numbers(const Source& s, const std::string& cls,
                                             const char* attr, std::size_t lo, std::size_t hi) {
    const std::optional<std::string> text = attribute(s, cls, attr);
    if (!text) return std::nullopt;
    std::vector<double> values;
    for (std::string_view token : xml::tokens(*text)) {
      const std::optional<double> v = xml::toDouble(token);
      if (!v || !std::isfinite(*v) || std::abs(*v) > 1e6)
        throw Error(s.where(), fmt::format("{}=\"{}\": '{}' is not a finite number in range", attr,
                                           *text, token));
      values.push_back(*v);
    }
    if (values.size() < lo || values.size() > hi)
      throw Error(s.where(),
                  fmt::format("{}=\"{}\" needs {} numbers", attr, *text,
                              lo == hi ? fmt::format("{}", lo) : fmt::format("{} to {}", lo, hi)));
    return values;
  }

  double number(const Source& s, const std::string& cls, const char* attr, double fallback) {
    const auto v = numbers(s, cls, attr, 1, 1);
    return v ? v->front() : fallback;
  }

  Vector3 vector3(const Source& s, const std::string& cls, const char* attr,
                  const Vector3& fallback) {
    const auto v = numbers(s, cls, attr, 3, 3);
    return v ? Vector3((*v)[0], (*v)[1], (*v)[2]) : fallback;
  }

  std::string text(const Source& s, const std::string& cls, const char* attr,
                   const std::string& fallback) const {
    return attribute(s, cls, attr).value_or(fallback);
  }

  double angle(double value) const { return degrees_ ? value * M_PI / 180.0 : value; }

  // --- <compiler>, <default>, <asset> --------------------------------------------------------

  void readCompiler(const Source& s) {
    const XMLElement& e = *s.element;
    if (const char* a = e.Attribute("angle")) {
      const std::string_view v(a);
      if (v != "degree" && v != "radian")
        throw Error(s.where(), fmt::format("angle=\"{}\": degree or radian", v));
      degrees_ = v == "degree";
    }
    if (const char* a = e.Attribute("assetdir")) meshdir_ = a;
    if (const char* a = e.Attribute("meshdir")) meshdir_ = a;
    if (const char* a = e.Attribute("eulerseq")) {
      const std::string v(a);
      if (v.size() != 3 || v.find_first_not_of("xyzXYZ") != std::string::npos)
        throw Error(s.where(), fmt::format("eulerseq=\"{}\": three of x, y, z, X, Y, Z", v));
      eulerseq_ = v;
    }
    if (const char* a = e.Attribute("autolimits")) autolimits_ = std::string_view(a) == "true";
  }

  // A <default> element: its class inherits `parent`'s attributes; nested defaults inherit it.
  void readDefaults(const Source& s, const std::string& fallback, const std::string& parent) {
    const char* own = s.element->Attribute("class");
    const std::string cls = own ? own : fallback;
    if (classes_.count(cls) && !(cls == "main" && parent.empty()))
      throw Error(s.where(), fmt::format("default class '{}' is defined twice", cls));
    auto& attrs = classes_[cls];
    if (!parent.empty()) attrs = classes_.at(parent);
    for (const Source& c : childrenOf(s)) {
      if (name(c) == "default") {
        if (!c.element->Attribute("class"))
          throw Error(c.where(), "a nested <default> needs a class attribute");
        readDefaults(c, "", cls);
        continue;
      }
      auto& tag = attrs[c.element->Name()];
      for (const tinyxml2::XMLAttribute* a = c.element->FirstAttribute(); a; a = a->Next())
        tag[a->Name()] = a->Value();
    }
  }

  void readAssets(const Source& s) {
    for (const Source& c : childrenOf(s)) {
      if (name(c) != "mesh") continue;
      const std::string cls = classOf(c, "main");
      const char* file = c.element->Attribute("file");
      if (!file) throw Error(c.where(), "a <mesh> without a file (inline vertex data) is not read");
      const char* given = c.element->Attribute("name");
      const std::string mesh_name = given ? given : fs::path(file).stem().string();
      MeshAsset asset;
      const fs::path folder = file_.parent_path() / meshdir_;
      asset.file = fs::path(file).is_absolute() ? fs::path(file) : folder / file;
      asset.scale = vector3(c, cls, "scale", Vector3::Ones());
      if (asset.scale.cwiseAbs().minCoeff() < 1e-12)
        throw Error(c.where(), fmt::format("mesh '{}': a zero scale", mesh_name));
      asset.refpos = units::kMetre * vector3(c, cls, "refpos", Vector3::Zero());
      if (const auto q = numbers(c, cls, "refquat", 4, 4))
        asset.refquat =
            xml::checkedQuaternion(*c.file, *c.element, (*q)[0], (*q)[1], (*q)[2], (*q)[3])
                .normalized();
      asset.source = c;
      if (!meshes_.emplace(mesh_name, asset).second)
        throw Error(c.where(), fmt::format("mesh '{}' is defined twice", mesh_name));
    }
  }

  // --- Frames -----------------------------------------------------------------------------------

  Quaternion euler(const Source& s, const Vector3& angles) const {
    Quaternion q = Quaternion::Identity();
    for (int i = 0; i < 3; ++i) {
      const char axis = eulerseq_[static_cast<std::size_t>(i)];
      const int k = std::tolower(axis) - 'x';
      const Quaternion turn(Eigen::AngleAxisd(angles[i], Vector3::Unit(k)));
      // Lower case: axes that turn with the frame (intrinsic); upper case: fixed axes.
      q = std::islower(axis) ? Quaternion(q * turn) : Quaternion(turn * q);
    }
    (void)s;
    return q;
  }

  // The frame an element's pos and orientation (quat, axisangle, euler, xyaxes or zaxis) give.
  Transform frame(const Source& s, const std::string& cls) {
    Transform t = Transform::Identity();
    t.translation() = units::kMetre * vector3(s, cls, "pos", Vector3::Zero());
    int given = 0;
    Quaternion q = Quaternion::Identity();
    if (const auto v = numbers(s, cls, "quat", 4, 4)) {
      q = xml::checkedQuaternion(*s.file, *s.element, (*v)[0], (*v)[1], (*v)[2], (*v)[3]);
      ++given;
    }
    if (const auto v = numbers(s, cls, "axisangle", 4, 4)) {
      const Vector3 axis((*v)[0], (*v)[1], (*v)[2]);
      if (axis.norm() < 1e-12) throw Error(s.where(), "axisangle: the axis is zero");
      q = Quaternion(Eigen::AngleAxisd(angle((*v)[3]), axis.normalized()));
      ++given;
    }
    if (const auto v = numbers(s, cls, "euler", 3, 3)) {
      q = euler(s, Vector3(angle((*v)[0]), angle((*v)[1]), angle((*v)[2])));
      ++given;
    }
    if (const auto v = numbers(s, cls, "xyaxes", 6, 6)) {
      const Vector3 x = Vector3((*v)[0], (*v)[1], (*v)[2]);
      Vector3 y((*v)[3], (*v)[4], (*v)[5]);
      if (x.norm() < 1e-12) throw Error(s.where(), "xyaxes: the x axis is zero");
      const Vector3 xn = x.normalized();
      y -= y.dot(xn) * xn;
      if (y.norm() < 1e-12) throw Error(s.where(), "xyaxes: the y axis is parallel to x");
      Matrix3 r;
      r.col(0) = xn;
      r.col(1) = y.normalized();
      r.col(2) = xn.cross(r.col(1));
      q = Quaternion(r);
      ++given;
    }
    if (const auto v = numbers(s, cls, "zaxis", 3, 3)) {
      const Vector3 z((*v)[0], (*v)[1], (*v)[2]);
      if (z.norm() < 1e-12) throw Error(s.where(), "zaxis: the axis is zero");
      q = Quaternion::FromTwoVectors(Vector3::UnitZ(), z.normalized());
      ++given;
    }
    if (given > 1)
      throw Error(s.where(), "more than one orientation (quat, axisangle, euler, xyaxes, zaxis)");
    t.linear() = q.normalized().toRotationMatrix();
    return t;
  }

  // --- <worldbody> ----------------------------------------------------------------------------

  void readBodies(const Source& parent_source, int parent, const std::string& childclass,
                  const Transform& prefix = Transform::Identity()) {
    for (const Source& c : childrenOf(parent_source)) {
      const std::string tag = name(c);
      if (tag == "body") {
        readBody(c, parent, childclass, prefix);
      } else if (tag == "frame") {  // a pure coordinate frame around its children
        const std::string cls = frameClass(c, childclass);
        readBodies(c, parent, cls, prefix * frame(c, cls));
      } else if (parent >= 0 && tag == "geom") {
        readGeom(c, parent, classOf(c, childclass), prefix);
      } else if (parent >= 0 && (tag == "joint" || tag == "freejoint")) {
        readJoint(c, parent, tag == "freejoint" ? "main" : classOf(c, childclass));
      } else if (parent >= 0 && tag == "inertial") {
        readInertial(c, parent, prefix);
      } else if (parent < 0 && tag == "geom") {
        // World geometry (a floor) is not part of the hand.
      }
    }
  }

  std::string frameClass(const Source& s, const std::string& childclass) const {
    const char* own = s.element->Attribute("childclass");
    if (!own) return childclass;
    if (!classes_.count(own))
      throw Error(s.where(), fmt::format("unknown default class '{}'", own));
    return own;
  }

  void readBody(const Source& s, int parent, const std::string& childclass,
                const Transform& prefix) {
    if (bodies_.size() >= kMaxBodies)
      throw Error(s.where(), fmt::format("more than {} bodies", kMaxBodies));
    MjBody body;
    const char* given = s.element->Attribute("name");
    body.name = given ? given : fmt::format("body{}", bodies_.size() + 1);
    body.source = s;
    body.parent = parent;
    const std::string cls = frameClass(s, childclass);
    body.local = prefix * frame(s, cls);
    const int index = static_cast<int>(bodies_.size());
    if (!body_index_.emplace(body.name, index).second)
      throw Error(s.where(), fmt::format("body '{}' is defined twice", body.name));
    bodies_.push_back(std::move(body));
    if (parent >= 0) bodies_[parent].children.push_back(index);
    readBodies(s, index, cls);
  }

  void readJoint(const Source& s, int body, const std::string& cls) {
    MjJoint j;
    const char* given = s.element->Attribute("name");
    j.name = given ? given
                   : fmt::format("{}_joint{}", bodies_[body].name, bodies_[body].joints.size() + 1);
    j.source = s;
    j.body = body;
    const std::string type = name(s) == "freejoint" ? "free" : text(s, cls, "type", "hinge");
    if (type == "free" || type == "ball") {
      if (bodies_[body].parent >= 0)
        throw Error(s.where(), fmt::format("joint '{}': a {} joint inside a hand has no graspkit "
                                           "form (hinge and slide joints are read)",
                                           j.name, type));
      warn(WarningKind::Robot, s.where(),
           fmt::format("joint '{}' ({}) moves the hand in the world: left out, the hand's pose "
                       "is the robot's transform",
                       j.name, type));
      left_out_joint_names_.insert(j.name);
      return;
    }
    if (type != "hinge" && type != "slide")
      throw Error(s.where(), fmt::format("joint '{}': unknown type '{}'", j.name, type));
    j.slide = type == "slide";
    const double unit = j.slide ? units::kMetre : 1.0;
    j.pos = units::kMetre * vector3(s, cls, "pos", Vector3::Zero());
    const Vector3 axis = vector3(s, cls, "axis", Vector3::UnitZ());
    if (axis.norm() < 1e-12) throw Error(s.where(), fmt::format("joint '{}': zero axis", j.name));
    j.axis = axis.normalized();
    const auto range = numbers(s, cls, "range", 2, 2);
    const std::string limited = text(s, cls, "limited", "auto");
    j.limited = limited == "true" || (limited == "auto" && autolimits_ && range.has_value());
    if (j.limited) {
      if (!range)
        throw Error(s.where(), fmt::format("joint '{}' is limited without a range", j.name));
      j.lo = j.slide ? unit * (*range)[0] : angle((*range)[0]);
      j.hi = j.slide ? unit * (*range)[1] : angle((*range)[1]);
      if (j.lo > j.hi)
        throw Error(s.where(), fmt::format("joint '{}': range {} {} is reversed", j.name,
                                           (*range)[0], (*range)[1]));
    } else if (j.slide) {
      throw Error(s.where(), fmt::format("joint '{}': a slide joint needs a range", j.name));
    } else {
      j.lo = -M_PI;
      j.hi = M_PI;
    }
    const double ref = number(s, cls, "ref", 0.0);
    j.ref = j.slide ? unit * ref : angle(ref);
    j.damping = number(s, cls, "damping", 0.0);
    j.frictionloss = number(s, cls, "frictionloss", 0.0);
    if (bodies_[body].parent < 0) {
      warn(WarningKind::Robot, s.where(),
           fmt::format("joint '{}' moves the hand in the world: left out, the hand's pose is "
                       "the robot's transform",
                       j.name));
      left_out_joint_names_.insert(j.name);
      return;
    }
    if (joints_.size() == static_cast<std::size_t>(kMaxRobotJoints))
      throw Error(s.where(), fmt::format("more than {} joints in one robot", kMaxRobotJoints));
    if (!joint_index_.emplace(j.name, static_cast<int>(joints_.size())).second)
      throw Error(s.where(), fmt::format("joint '{}' is defined twice", j.name));
    bodies_[body].joints.push_back(static_cast<int>(joints_.size()));
    joints_.push_back(std::move(j));
  }

  void readInertial(const Source& s, int body, const Transform& prefix) {
    MjBody& b = bodies_[body];
    const Transform at = prefix * frame(s, "main");
    const auto mass = numbers(s, "main", "mass", 1, 1);
    if (!mass) throw Error(s.where(), "<inertial> needs a mass");
    if ((*mass)[0] < 0.0) throw Error(s.where(), "<inertial>: a negative mass");
    Matrix3 local = Matrix3::Zero();
    if (const auto d = numbers(s, "main", "diaginertia", 3, 3)) {
      local.diagonal() << (*d)[0], (*d)[1], (*d)[2];
    } else if (const auto f = numbers(s, "main", "fullinertia", 6, 6)) {
      local << (*f)[0], (*f)[3], (*f)[4], (*f)[3], (*f)[1], (*f)[5], (*f)[4], (*f)[5], (*f)[2];
    } else {
      throw Error(s.where(), "<inertial> needs diaginertia or fullinertia");
    }
    b.hasInertial = true;
    b.mass = (*mass)[0] * units::kKilogram;
    b.cog = at.translation();
    b.inertia = at.linear() * local * at.linear().transpose() *
                (units::kKilogram * units::kMetre * units::kMetre);
  }

  void readGeom(const Source& s, int body, const std::string& cls, const Transform& prefix) {
    const int contype = static_cast<int>(number(s, cls, "contype", 1));
    const int conaffinity = static_cast<int>(number(s, cls, "conaffinity", 1));
    const std::string type = text(s, cls, "type", "sphere");
    Transform placed = prefix * frame(s, cls);
    const auto size = numbers(s, cls, "size", 0, 3);
    auto sizeAt = [&](std::size_t i) {
      if (!size || size->size() <= i)
        throw Error(s.where(), fmt::format("a {} geom needs {} size values", type, i + 1));
      if (!((*size)[i] > 0.0))
        throw Error(s.where(), fmt::format("a {} geom's size must be positive", type));
      return units::kMetre * (*size)[i];
    };
    double half_length = -1.0;  // from fromto
    if (const auto ft = numbers(s, cls, "fromto", 6, 6);
        ft && (type == "capsule" || type == "cylinder" || type == "box" || type == "ellipsoid")) {
      const Vector3 a = units::kMetre * Vector3((*ft)[0], (*ft)[1], (*ft)[2]);
      const Vector3 b = units::kMetre * Vector3((*ft)[3], (*ft)[4], (*ft)[5]);
      if ((b - a).norm() < 1e-9) throw Error(s.where(), "fromto: the two points coincide");
      placed = prefix;
      Transform along = Transform::Identity();
      along.translation() = 0.5 * (a + b);
      along.linear() =
          Quaternion::FromTwoVectors(Vector3::UnitZ(), (b - a).normalized()).toRotationMatrix();
      placed = prefix * along;
      half_length = 0.5 * (b - a).norm();
    }
    TriangleMesh mesh;
    if (type == "sphere") {
      mesh = geometry::sphereMesh(sizeAt(0));
    } else if (type == "capsule") {
      mesh = geometry::capsuleMesh(sizeAt(0), 2.0 * (half_length >= 0 ? half_length : sizeAt(1)));
    } else if (type == "cylinder") {
      mesh = geometry::cylinderMesh(sizeAt(0), 2.0 * (half_length >= 0 ? half_length : sizeAt(1)));
    } else if (type == "box") {
      mesh = geometry::boxMesh(
          2.0 * Vector3(sizeAt(0), sizeAt(1), half_length >= 0 ? half_length : sizeAt(2)));
    } else if (type == "ellipsoid") {
      mesh = geometry::sphereMesh(1.0);
      Eigen::Affine3d scaling = Eigen::Affine3d::Identity();
      scaling.linear() =
          Vector3(sizeAt(0), sizeAt(1), half_length >= 0 ? half_length : sizeAt(2)).asDiagonal();
      transformMesh(mesh, scaling);
    } else if (type == "mesh") {
      mesh = meshGeometry(s, cls, body);
    } else if (type == "plane" || type == "hfield" || type == "sdf") {
      warn(WarningKind::Geometry, s.where(),
           fmt::format("a {} geom on a hand body is left out", type));
      return;
    } else {
      throw Error(s.where(), fmt::format("unknown geom type '{}'", type));
    }
    // Mass for bodies without <inertial>: the geom's mass, else density x volume.
    if (const auto m = numbers(s, cls, "mass", 1, 1)) {
      bodies_[body].geomMass += (*m)[0] * units::kKilogram;
    } else {
      const MassProperties props = computeMassProperties(mesh);
      const double density = number(s, cls, "density", 1000.0);                            // kg/m^3
      if (props.valid) bodies_[body].geomMass += std::abs(props.volume) * density * 1e-6;  // g
    }
    // Visual-only geoms (contype and conaffinity 0) never collide in MuJoCo: left out.
    if (contype == 0 && conaffinity == 0) return;
    // MuJoCo collides a mesh geom as its convex hull, and hands are tuned to that: their
    // collision meshes are often the visual ones, tens of thousands of triangles whose contact
    // search dominated planning and simulation. A flat mesh has no hull and stays as it is.
    if (type == "mesh" && options_.mjcfMeshHulls) {
      if (auto hull = geometry::convexHullMesh(mesh.vertices)) mesh = std::move(*hull);
    }
    appendMesh(bodies_[body].mesh, std::move(mesh), placed);
  }

  TriangleMesh meshGeometry(const Source& s, const std::string& cls, int body) {
    const std::optional<std::string> mesh_name = attribute(s, cls, "mesh");
    if (!mesh_name) throw Error(s.where(), "a mesh geom needs a mesh attribute");
    const auto asset = meshes_.find(*mesh_name);
    if (asset == meshes_.end())
      throw Error(s.where(), fmt::format("mesh '{}' is not in <asset>", *mesh_name));
    const MeshAsset& a = asset->second;
    auto cached = loaded_.find(a.file);
    if (cached == loaded_.end()) {
      try {
        cached = loaded_.emplace(a.file, loadMesh(a.file)).first;
      } catch (const Error& e) {
        throw Error(a.source.where(), fmt::format("mesh '{}': {}", *mesh_name, e.what()));
      }
    }
    TriangleMesh mesh = cached->second;
    // MuJoCo: vertices scaled, then taken relative to refpos and turned by refquat's conjugate.
    Eigen::Affine3d to_mm = Eigen::Affine3d::Identity();
    to_mm.linear() = (units::kMetre * a.scale).asDiagonal();
    Eigen::Affine3d reference = Eigen::Affine3d::Identity();
    reference.linear() = a.refquat.conjugate().toRotationMatrix();
    reference = reference * Eigen::Translation3d(-a.refpos);
    transformMesh(mesh, reference * to_mm);
    // A mirroring scale (MuJoCo allows one) turns the surface inside out: keep it outward.
    if (a.scale.prod() < 0.0)
      for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    if (bodies_[body].meshFile.empty()) bodies_[body].meshFile = a.file.string();
    return mesh;
  }

  // --- Tendons, actuators, equalities ------------------------------------------------------

  void readTendons(const Source& s) {
    for (const Source& c : childrenOf(s)) {
      if (name(c) != "fixed") continue;  // spatial tendons move no joint by themselves
      const char* given = c.element->Attribute("name");
      if (!given) continue;  // only a named tendon can be actuated
      std::vector<std::pair<int, double>> joints;
      for (const Source& j : childrenOf(c)) {
        if (name(j) != "joint") continue;
        const char* joint = j.element->Attribute("joint");
        const int index = jointIndex(j, joint);
        if (index < 0) continue;  // a joint left out (on the hand's root)
        joints.emplace_back(index, number(j, "main", "coef", 1.0));
      }
      tendons_[given] = {c, joints};
    }
  }

  // A joint's index; -1 for a joint left out; an error for a name the file does not have.
  int jointIndex(const Source& where, const char* joint) const {
    if (!joint) throw Error(where.where(), "a joint attribute is needed");
    const auto it = joint_index_.find(joint);
    if (it != joint_index_.end()) return it->second;
    if (left_out_joint_names_.count(joint)) return -1;
    throw Error(where.where(), fmt::format("joint '{}' is not in the file", joint));
  }

  void readActuators(const Source& s) {
    for (const Source& c : childrenOf(s)) {
      const std::string cls = classOf(c, "main");
      DofSpec spec;
      const char* given = c.element->Attribute("name");
      spec.name = given ? given : fmt::format("actuator{}", actuators_.size() + 1);
      spec.source = c;
      spec.kp = number(c, cls, "kp", 0.0);
      if (const auto f = numbers(c, cls, "forcerange", 2, 2))
        spec.effort = std::max(std::abs((*f)[0]), std::abs((*f)[1]));
      std::vector<std::pair<int, double>> targets;
      if (const char* joint = c.element->Attribute("joint")) {
        const int index = jointIndex(c, joint);
        if (index < 0) continue;  // drives a joint that moves the whole hand
        targets.emplace_back(index, 1.0);
      } else if (const char* tendon = c.element->Attribute("tendon")) {
        const auto t = tendons_.find(tendon);
        if (t == tendons_.end())
          throw Error(c.where(),
                      fmt::format("tendon '{}' is not a fixed tendon of the file", tendon));
        targets = t->second.second;
      } else {
        warn(WarningKind::Robot, c.where(),
             fmt::format("actuator '{}' drives no joint or fixed tendon: left out", spec.name));
        continue;
      }
      if (targets.empty()) continue;
      if (actuators_.size() == static_cast<std::size_t>(kMaxRobotDofs))
        throw Error(c.where(), fmt::format("more than {} DOFs in one robot", kMaxRobotDofs));
      actuators_.push_back({spec, targets});
    }
  }

  // One DOF per actuator; a joint is driven by the first actuator that reaches it, relative to
  // the first joint of that actuator (a tendon's joints in the ratio of their coefficients).
  void makeDofs() {
    for (const auto& [spec, targets] : actuators_) {
      const int dof = static_cast<int>(dofs_.size());
      bool any = false;
      const double first = targets.front().second;
      for (const auto& [joint, coef] : targets) {
        if (drives_[joint].dof >= 0 || std::abs(coef) < 1e-12) continue;
        drives_[joint] = {dof, coef / first, 0.0};
        any = true;
      }
      if (!any) {
        warn(WarningKind::Robot, spec.source.where(),
             fmt::format("actuator '{}' drives only joints another actuator drives: left out",
                         spec.name));
        continue;
      }
      dofs_.push_back(spec);
    }
    if (!actuators_.empty()) return;
    // No actuators: every joint is a DOF, as in a URDF.
    if (joints_.size() > static_cast<std::size_t>(kMaxRobotDofs))
      throw Error(joints_[kMaxRobotDofs].source.where(),
                  fmt::format("more than {} DOFs in one robot", kMaxRobotDofs));
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      drives_[j] = {static_cast<int>(dofs_.size()), 1.0, 0.0};
      dofs_.push_back({joints_[j].name, joints_[j].source, 0.0, 0.0});
    }
  }

  // <equality><joint joint1 joint2 polycoef>: joint1 = c0 + c1 joint2 (higher terms refused).
  void readJointEqualities(const Source& s) {
    std::vector<Source> pending;
    for (const Source& c : childrenOf(s))
      if (name(c) == "joint") pending.push_back(c);
    // Couple until nothing changes: an equality may wait for another to drive its joint.
    for (bool changed = true; changed;) {
      changed = false;
      for (auto it = pending.begin(); it != pending.end();) {
        if (coupleJoints(*it)) {
          it = pending.erase(it);
          changed = true;
        } else {
          ++it;
        }
      }
    }
    for (const Source& c : pending) {
      warn(WarningKind::Robot, c.where(),
           "a joint equality between joints no actuator drives: both frozen at their reference");
    }
  }

  bool coupleJoints(const Source& c) {
    const int a = jointIndex(c, c.element->Attribute("joint1"));
    const char* second = c.element->Attribute("joint2");
    const auto poly = numbers(c, "main", "polycoef", 1, 5);
    std::vector<double> k = poly.value_or(std::vector<double>{0, 1, 0, 0, 0});
    k.resize(5, 0.0);
    for (std::size_t i = 2; i < 5; ++i)
      if (std::abs(k[i]) > 0.0)
        throw Error(c.where(),
                    "polycoef with quadratic or higher terms is not read (a linear "
                    "coupling is)");
    if (a < 0) return true;
    const MjJoint& ja = joints_[a];
    const double unit_a = ja.slide ? units::kMetre : 1.0;
    if (!second) {  // joint1 held at c0
      if (drives_[a].dof < 0) frozen_[a] = unit_a * k[0];
      return true;
    }
    const int b = jointIndex(c, second);
    if (b < 0) return true;
    const double unit_b = joints_[b].slide ? units::kMetre : 1.0;
    // In graspkit units: qa = c0' + c1' qb.
    const double c0 = unit_a * k[0], c1 = k[1] * unit_a / unit_b;
    Drive& da = drives_[a];
    Drive& db = drives_[b];
    if (db.dof >= 0 && da.dof < 0) {
      da = {db.dof, c1 * db.ratio, c0 + c1 * db.offset};
      return true;
    }
    if (da.dof >= 0 && db.dof < 0) {
      if (std::abs(c1) < 1e-12) return true;
      db = {da.dof, da.ratio / c1, (da.offset - c0) / c1};
      return true;
    }
    if (da.dof >= 0 && db.dof >= 0) {
      const bool agree = da.dof == db.dof && std::abs(da.ratio - c1 * db.ratio) < 1e-6 &&
                         std::abs(da.offset - (c0 + c1 * db.offset)) < 1e-6;
      if (!agree)
        warn(WarningKind::Robot, c.where(),
             fmt::format("joint equality '{}' = f('{}') disagrees with the actuators that drive "
                         "both; the actuators' coupling is kept",
                         ja.name, joints_[b].name));
      return true;
    }
    return false;  // neither driven yet
  }

  // --- Loops: <equality><connect> -------------------------------------------------------------

  // A joint's motion at value q (relative to its reference).
  Transform jointMotion(const MjJoint& j, double q) const {
    Transform m = Transform::Identity();
    const double v = q - j.ref;
    if (j.slide) {
      m.translation() = v * j.axis;
    } else {
      m = Eigen::Translation3d(j.pos) * Eigen::AngleAxisd(v, j.axis) * Eigen::Translation3d(-j.pos);
    }
    return m;
  }

  // The world frame of `body` for joint values `q` (all joints, graspkit units).
  Transform bodyPose(int body, const std::vector<double>& q) const {
    Transform pose = Transform::Identity();
    std::vector<int> path;
    for (int b = body; b >= 0; b = bodies_[b].parent) path.push_back(b);
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      pose = pose * bodies_[*it].local;
      for (const int j : bodies_[*it].joints) pose = pose * jointMotion(joints_[j], q[j]);
    }
    return pose;
  }

  std::vector<int> jointsAbove(int body) const {
    std::vector<int> out;
    for (int b = body; b >= 0; b = bodies_[b].parent)
      out.insert(out.end(), bodies_[b].joints.begin(), bodies_[b].joints.end());
    return out;
  }

  // Joint values (graspkit units) with DOF `dof` at `value`, passive joints from `passive`.
  std::vector<double> valuesAt(int dof, double value, const std::vector<int>& passive,
                               const Eigen::VectorXd& x) const {
    std::vector<double> q(joints_.size());
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      const Drive& d = drives_[j];
      q[j] = d.dof == dof ? d.ratio * value + d.offset : (d.dof >= 0 ? d.offset : joints_[j].ref);
      if (frozen_.count(static_cast<int>(j))) q[j] = frozen_.at(static_cast<int>(j));
    }
    for (std::size_t k = 0; k < passive.size(); ++k) q[passive[k]] = x[static_cast<long>(k)];
    return q;
  }

  void readConnects(const Source& s) {
    for (const Source& c : childrenOf(s))
      if (name(c) == "connect") closeLoop(c);
  }

  int bodyIndex(const Source& where, const char* body) const {
    if (!body) throw Error(where.where(), "<connect> needs body1 and body2 (sites are not read)");
    const auto it = body_index_.find(body);
    if (it == body_index_.end())
      throw Error(where.where(), fmt::format("body '{}' is not in the file", body));
    return it->second;
  }

  void closeLoop(const Source& c) {
    const int b1 = bodyIndex(c, c.element->Attribute("body1"));
    const char* second = c.element->Attribute("body2");
    const int b2 = second ? bodyIndex(c, second) : -1;
    const Vector3 anchor = units::kMetre * vector3(c, "main", "anchor", Vector3::Zero());
    // The passive joints on either side, and the one DOF that drives the loop.
    std::vector<int> passive;
    std::set<int> loop_dofs;
    std::vector<int> above = jointsAbove(b1);
    if (b2 >= 0) {
      const std::vector<int> other = jointsAbove(b2);
      above.insert(above.end(), other.begin(), other.end());
    }
    for (const int j : above) {
      if (drives_[j].dof >= 0)
        loop_dofs.insert(drives_[j].dof);
      else if (!frozen_.count(j) && std::find(passive.begin(), passive.end(), j) == passive.end())
        passive.push_back(j);
    }
    if (passive.empty()) return;  // nothing left to move: the loop holds or is the DOFs' matter
    if (loop_dofs.size() != 1)
      throw Error(c.where(),
                  fmt::format("a loop through {} DOFs is not closed by graspkit (one DOF per "
                              "loop is)",
                              loop_dofs.size()));
    const int dof = *loop_dofs.begin();
    // The anchor in body2's frame where the model is built (every joint at its reference).
    std::vector<double> q0(joints_.size());
    for (std::size_t j = 0; j < joints_.size(); ++j) q0[j] = joints_[j].ref;
    const Vector3 world_anchor = bodyPose(b1, q0) * anchor;
    const Vector3 anchor2 =
        b2 >= 0 ? Vector3(bodyPose(b2, q0).inverse() * world_anchor) : world_anchor;
    auto gap = [&](double value, const Eigen::VectorXd& x) -> Vector3 {
      const std::vector<double> q = valuesAt(dof, value, passive, x);
      const Vector3 p1 = bodyPose(b1, q) * anchor;
      const Vector3 p2 = b2 >= 0 ? Vector3(bodyPose(b2, q) * anchor2) : anchor2;
      return p1 - p2;
    };
    const auto [lo, hi] = dofRange(dof);
    // Start where the model is built: the DOF value putting its first joint at its reference.
    double start = 0.0;
    for (std::size_t j = 0; j < joints_.size(); ++j)
      if (drives_[j].dof == dof) {
        start = (joints_[j].ref - drives_[j].offset) / drives_[j].ratio;
        break;
      }
    start = std::clamp(start, lo, hi);
    Eigen::VectorXd x0(static_cast<long>(passive.size()));
    for (std::size_t k = 0; k < passive.size(); ++k)
      x0[static_cast<long>(k)] = joints_[passive[k]].ref;
    std::vector<std::pair<double, Eigen::VectorXd>> samples;
    double worst = 0.0;
    for (const int direction : {+1, -1}) {
      Eigen::VectorXd x = x0;
      for (int i = direction > 0 ? 0 : 1; i <= kLoopSamples; ++i) {
        const double value = direction > 0 ? start + (hi - start) * i / kLoopSamples
                                           : start - (start - lo) * i / kLoopSamples;
        x = solveLoop(gap, value, x);
        worst = std::max(worst, gap(value, x).norm());
        samples.emplace_back(value, x);
      }
    }
    if (worst > 1e-3)
      warn(WarningKind::Robot, c.where(),
           fmt::format("the loop cannot be closed everywhere in the DOF's range (it stays {:.3g} "
                       "mm open at worst)",
                       worst));
    // Each passive joint follows the DOF along the least-squares line through the solutions.
    Eigen::MatrixXd a(static_cast<long>(samples.size()), 2);
    for (std::size_t i = 0; i < samples.size(); ++i)
      a.row(static_cast<long>(i)) << samples[i].first, 1.0;
    for (std::size_t k = 0; k < passive.size(); ++k) {
      Eigen::VectorXd b(static_cast<long>(samples.size()));
      for (std::size_t i = 0; i < samples.size(); ++i)
        b[static_cast<long>(i)] = samples[i].second[static_cast<long>(k)];
      const Eigen::Vector2d line = a.colPivHouseholderQr().solve(b);
      drives_[passive[k]] = {dof, line[0], line[1]};
      followers_.insert(passive[k]);
    }
    // How far the linear coupling leaves the loop open.
    double open = 0.0;
    Eigen::VectorXd none(0);
    std::vector<int> no_passive;
    for (const auto& [value, x] : samples) {
      const std::vector<double> q = valuesAt(dof, value, no_passive, none);
      const Vector3 p1 = bodyPose(b1, q) * anchor;
      const Vector3 p2 = b2 >= 0 ? Vector3(bodyPose(b2, q) * anchor2) : anchor2;
      open = std::max(open, (p1 - p2).norm());
    }
    loop_gaps_.push_back(open);
    if (open > kLoopWarnGap)
      warn(WarningKind::Robot, c.where(),
           fmt::format("the loop's passive joints follow DOF {} linearly, which leaves it up to "
                       "{:.2f} mm open within the DOF's range",
                       dof, open));
  }

  // Gauss-Newton with a numeric Jacobian and a damped step: the passive joint values near `x`
  // that close the loop at DOF `value`.
  template <class Gap>
  Eigen::VectorXd solveLoop(const Gap& gap, double value, Eigen::VectorXd x) const {
    for (int iteration = 0; iteration < 50; ++iteration) {
      const Vector3 r = gap(value, x);
      if (r.norm() < kLoopSolveTolerance) break;
      Eigen::MatrixXd jac(3, x.size());
      for (long k = 0; k < x.size(); ++k) {
        Eigen::VectorXd step = x;
        step[k] += 1e-7;
        jac.col(k) = (gap(value, step) - r) / 1e-7;
      }
      const Eigen::MatrixXd normal =
          jac.transpose() * jac + 1e-9 * Eigen::MatrixXd::Identity(x.size(), x.size());
      x -= normal.ldlt().solve(jac.transpose() * r);
    }
    return x;
  }

  // A DOF's range from the joints that drive it first (followers' own limits do not narrow it).
  std::pair<double, double> dofRange(int dof) const {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      const Drive& d = drives_[j];
      if (d.dof != dof || followers_.count(static_cast<int>(j))) continue;
      double a = (joints_[j].lo - d.offset) / d.ratio, b = (joints_[j].hi - d.offset) / d.ratio;
      if (a > b) std::swap(a, b);
      lo = std::max(lo, a);
      hi = std::min(hi, b);
    }
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {-M_PI, M_PI};
    return {lo, hi};
  }

  void readExclusions(const Source& s) {
    for (const Source& c : childrenOf(s)) {
      if (name(c) != "exclude") continue;
      exclusions_.emplace_back(bodyIndex(c, c.element->Attribute("body1")),
                               bodyIndex(c, c.element->Attribute("body2")));
    }
  }

  // --- The graspkit model ------------------------------------------------------------------------

  // A body moves against its parent when one of its joints is driven.
  bool moves(int body) const {
    for (const int j : bodies_[body].joints)
      if (drives_[j].dof >= 0) return true;
    return false;
  }

  // The bodies fixed to `body` (itself first), each with its frame in `body`'s frame.
  std::vector<std::pair<int, Transform>> rigidGroup(int body) const {
    std::vector<std::pair<int, Transform>> group{{body, Transform::Identity()}};
    for (std::size_t i = 0; i < group.size(); ++i) {
      for (const int child : bodies_[group[i].first].children) {
        if (moves(child)) continue;
        group.emplace_back(child, group[i].second * fixedLocal(child));
      }
    }
    return group;
  }

  // A body's frame in its parent's for a body whose joints are all frozen.
  Transform fixedLocal(int body) const {
    Transform t = bodies_[body].local;
    for (const int j : bodies_[body].joints) {
      const auto f = frozen_.find(j);
      t = t * jointMotion(joints_[j], f != frozen_.end() ? f->second : joints_[j].ref);
    }
    return t;
  }

  // The moving bodies hung on `body`'s rigid group.
  std::vector<int> movingChildren(int body) const {
    std::vector<int> out;
    for (const auto& [member, frame] : rigidGroup(body))
      for (const int child : bodies_[member].children)
        if (moves(child)) out.push_back(child);
    return out;
  }

  std::shared_ptr<const BodyModel> groupBody(const std::vector<std::pair<int, Transform>>& group,
                                             const std::string& body_name) {
    auto body = std::make_shared<BodyModel>();
    body->name = body_name;
    body->file = file_;
    body->material = options_.urdfMaterial;
    const auto own = options_.urdfLinkMaterials.find(body_name);
    if (own != options_.urdfLinkMaterials.end()) body->material = own->second;
    TriangleMesh mesh;
    double mass = 0.0;
    Vector3 moment = Vector3::Zero();
    Matrix3 inertia = Matrix3::Zero();  // about the group origin
    for (const auto& [member, frame] : group) {
      const MjBody& b = bodies_[member];
      appendMesh(mesh, b.mesh, frame);
      if (body->geometryFile.empty() && !b.meshFile.empty()) body->geometryFile = b.meshFile;
      const double m = b.hasInertial ? b.mass : b.geomMass;
      if (m <= 0.0) continue;
      const Vector3 c = frame * (b.hasInertial ? b.cog : Vector3::Zero());
      const Matrix3 local = b.hasInertial
                                ? Matrix3(frame.linear() * b.inertia * frame.linear().transpose())
                                : Matrix3::Zero();
      inertia += local + m * (c.squaredNorm() * Matrix3::Identity() - c * c.transpose());
      mass += m;
      moment += m * c;
    }
    body->mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    io::setLinkMassProperties(*body, mass, moment, inertia);
    return body;
  }

  std::shared_ptr<const RobotModel> build(const char* model_name) {
    auto robot = std::make_shared<RobotModel>();
    robot->file = file_;
    robot->name = model_name && *model_name ? model_name : file_.stem().string();
    robot->type = "Hand";
    robot->dbName = robot->name;
    robot->isHand = true;
    Registry& registry = options_.registry ? *options_.registry : Registry::global();
    robot->robotType = registry.robotType("Hand");
    robot->typeProvider = "MJCF";
    for (const DofSpec& spec : dofs_) {
      Dof dof;
      dof.type = DofType::Rigid;
      robot->dofs.push_back(dof);
      (void)spec;
    }
    // The palm: every body fixed to the world, in the frame of the first top-level body.
    std::vector<int> tops;
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (bodies_[b].parent < 0) tops.push_back(static_cast<int>(b));
    const Transform palm_frame = fixedLocal(tops.front());
    std::vector<std::pair<int, Transform>> palm;
    for (const int top : tops) {
      if (moves(top)) continue;  // unreachable: a top body's joints are left out
      for (const auto& [member, frame] : rigidGroup(top))
        palm.emplace_back(member, palm_frame.inverse() * fixedLocal(top) * frame);
    }
    robot->palmFile = bodies_[tops.front()].name;
    robot->palm = groupBody(palm, robot->palmFile);
    std::map<int, LinkRef> link_of;  // MJCF body -> graspkit link
    for (const auto& [member, frame] : palm) link_of[member] = LinkRef{};
    std::vector<std::pair<int, Transform>> firsts;  // moving bodies on the palm, with parent frame
    for (const auto& [member, frame] : palm)
      for (const int child : bodies_[member].children)
        if (moves(child)) firsts.emplace_back(child, frame);
    for (const auto& [first, parent_frame] : firsts)
      for (const std::vector<int>& path : pathsFrom(first))  // a branching tree: one per leaf
        readChain(path, parent_frame, *robot, link_of);
    if (robot->chains.empty())
      throw Error(xml::at(file_, *bodies_.front().source.element),
                  "no driven joint below the hand's fixed bodies: nothing moves");
    finishDofs(*robot);
    for (const auto& [a, b] : exclusions_) {
      const auto la = link_of.find(a), lb = link_of.find(b);
      if (la == link_of.end() || lb == link_of.end() || la->second == lb->second) continue;
      const bool listed = std::any_of(robot->disabledCollisions.begin(),
                                      robot->disabledCollisions.end(), [&](const CollisionPair& p) {
                                        return (p.first == la->second && p.second == lb->second) ||
                                               (p.first == lb->second && p.second == la->second);
                                      });
      if (listed) continue;  // two excluded bodies merged into the same links
      robot->disabledCollisions.push_back({la->second, lb->second, "MJCF <contact><exclude>"});
    }
    robot->eigengrasps = identityEigengrasps(static_cast<int>(robot->dofs.size()));
    if (options_.switchOffInherentCollisions) disableInherentSelfCollisions(*robot);
    if (options_.inferClosingDirections)
      setClosingDirections(*robot, inferClosingDirections(*robot));
    // The hand setup's virtual contacts: the palm's and the fingertips' (virtual_contact.hpp).
    robot->virtualContacts = deriveFingertipContacts(Robot(robot));
    return robot;
  }

  // Every path of moving bodies from `first` down to a leaf. A finger tree that branches below
  // a moving joint gives one chain per path; a shared body's joints are repeated in each chain,
  // driven by their DOFs, and the body's link belongs to the first chain.
  std::vector<std::vector<int>> pathsFrom(int first) const {
    std::vector<std::vector<int>> out;
    std::vector<int> path;
    std::size_t joints = 0;
    std::function<void(int)> walk = [&](int b) {
      path.push_back(b);
      const std::vector<int> next = movingChildren(b);
      if (next.empty()) {
        for (const int p : path) joints += bodies_[p].joints.size();
        if (joints > kMaxChainJoints)
          throw Error(bodies_[first].source.where(),
                      fmt::format("the tree below body '{}' repeats its shared joints into more "
                                  "than {} chain joints",
                                  bodies_[first].name, kMaxChainJoints));
        out.push_back(path);
      }
      for (const int n : next) walk(n);
      path.pop_back();
    };
    walk(first);
    return out;
  }

  void readChain(const std::vector<int>& path, const Transform& parent_frame, RobotModel& robot,
                 std::map<int, LinkRef>& link_of) {
    // The chain's moving bodies, each with its frame (palm frame, every joint at reference).
    const std::vector<int>& chain_bodies = path;
    std::vector<Transform> frames;
    Transform parent = parent_frame;
    for (std::size_t i = 0; i < path.size(); ++i) {
      const int b = path[i];
      const Transform at = parent * bodies_[b].local;
      frames.push_back(at);
      if (i + 1 == path.size()) break;
      // The next moving body hangs on a member of b's rigid group.
      Transform member = Transform::Identity();
      for (int up = bodies_[path[i + 1]].parent; up != b; up = bodies_[up].parent)
        member = fixedLocal(up) * member;
      parent = at * member;
    }
    // Joint axes (palm frame) in chain order.
    struct AxisJoint {
      int joint;
      Vector3 point, axis;
    };
    std::vector<AxisJoint> axes;
    for (std::size_t i = 0; i < chain_bodies.size(); ++i) {
      Transform at = frames[i];
      for (const int j : bodies_[chain_bodies[i]].joints) {
        const MjJoint& mj = joints_[j];
        if (drives_[j].dof < 0) {  // frozen: a fixed motion within the body
          at = at * jointMotion(mj, frozen_.count(j) ? frozen_.at(j) : mj.ref);
          continue;
        }
        axes.push_back({j, at * mj.pos, (at.linear() * mj.axis).normalized()});
      }
    }
    KinematicChain chain;
    chain.firstJoint = robot.jointCount();
    Transform before = Transform::Identity();
    before.linear() = io::frameWithZ(axes[0].axis, Vector3::UnitX());
    before.translation() = axes[0].point;
    chain.base = before;
    std::size_t next_axis = 0;
    int consumed = 0;  // joints since the last link
    for (std::size_t i = 0; i < chain_bodies.size(); ++i) {
      const MjBody& body = bodies_[chain_bodies[i]];
      Transform after = before;
      for (const int j : body.joints) {
        if (drives_[j].dof < 0) continue;
        const MjJoint& mj = joints_[j];
        Joint dh;
        dh.type = mj.slide ? JointType::Prismatic : JointType::Revolute;
        if (next_axis + 1 < axes.size()) {
          io::denavitHartenbergTo(before, axes[next_axis + 1].point, axes[next_axis + 1].axis, dh,
                                  after);
        } else {
          after = before * dh.transform(0.0);
        }
        const Drive& d = drives_[j];
        dh.dof = d.dof;
        dh.ratio = d.ratio;
        // MJCF: the joint turns by q - ref with q = ratio DOF + offset; graspkit: value =
        // ratio DOF, the rest in the driven DH parameter.
        (dh.type == JointType::Prismatic ? dh.d : dh.theta) += d.offset - mj.ref;
        dh.min = mj.lo - d.offset;
        dh.max = mj.hi - d.offset;
        const double unit = mj.slide ? units::kNewton / units::kMetre : units::kNewtonMetre;
        dh.viscousFriction = mj.damping * unit;
        dh.coulombFriction = mj.frictionloss * (mj.slide ? units::kNewton : units::kNewtonMetre);
        chain.joints.push_back(dh);
        build_order_.push_back(j);
        before = after;
        ++next_axis;
        ++consumed;
      }
      // The link: this body's rigid group, at the body's MJCF frame (all joints at reference).
      // A body an earlier chain of the same tree holds: the next link takes its joints too.
      if (consumed == 0 || link_of.count(chain_bodies[i])) continue;
      Link link;
      link.name = body.name;
      link.file = body.name;
      link.jointType = consumed == 2   ? DynamicJointType::Universal
                       : consumed >= 3 ? DynamicJointType::Ball
                       : chain.joints.back().type == JointType::Prismatic
                           ? DynamicJointType::Prismatic
                           : DynamicJointType::Revolute;
      link.lastJoint = static_cast<int>(chain.joints.size()) - 1;
      link.frame = after.inverse() * frames[i];
      const auto group = rigidGroup(chain_bodies[i]);
      link.body = groupBody(group, body.name);
      const LinkRef ref{static_cast<int>(robot.chains.size()),
                        static_cast<int>(chain.links.size())};
      for (const auto& [member, frame] : group) link_of[member] = ref;
      chain.links.push_back(std::move(link));
      consumed = 0;
    }
    robot.chains.push_back(std::move(chain));
  }

  void finishDofs(RobotModel& robot) {
    // Followers (loop joints, and joints coupled by equalities) never narrow a DOF's range: a
    // follower's limits widen to what the DOF asks, with a warning when that passes them.
    for (std::size_t d = 0; d < robot.dofs.size(); ++d) {
      const auto [lo, hi] = dofRange(static_cast<int>(d));
      for (KinematicChain& chain : robot.chains) {
        for (std::size_t j = 0; j < chain.joints.size(); ++j) {
          Joint& joint = chain.joints[j];
          if (joint.dof != static_cast<int>(d)) continue;
          double a = joint.ratio * lo, b = joint.ratio * hi;
          if (a > b) std::swap(a, b);
          if (a < joint.min - 1e-9 || b > joint.max + 1e-9) {
            const int mj = mjJointOf(joint, chain, j);
            constexpr double kTolerance = 0.05;  // rad or mm a loop's line may overshoot
            if (mj >= 0 && (a < joint.min - kTolerance || b > joint.max + kTolerance))
              warn(WarningKind::Robot, joints_[mj].source.where(),
                   fmt::format("joint '{}' follows DOF {} past its own range [{:.4g}, {:.4g}] "
                               "(to [{:.4g}, {:.4g}]); the range does not narrow the DOF's",
                               joints_[mj].name, d, joint.min, joint.max, a, b));
            joint.min = std::min(joint.min, a);
            joint.max = std::max(joint.max, b);
          }
        }
      }
    }
    model::gatherDofJoints(robot);
    for (std::size_t d = 0; d < robot.dofs.size(); ++d) {
      Dof& dof = robot.dofs[d];
      const DofSpec& spec = dofs_[d];
      if (dof.joints.empty()) {
        dof.min = dof.max = 0.0;
        continue;
      }
      if (dof.min > dof.max)
        throw Error(spec.source.where(),
                    fmt::format("actuator '{}': its joints' ranges do not overlap", spec.name));
      const Joint& first = robot.joint(dof.joints.front());
      const bool prismatic = first.type == JointType::Prismatic;
      dof.defaultVelocity = prismatic ? 10.0 : 1.0;
      dof.Kp = prismatic ? kPrismaticKp : kRevoluteKp;
      dof.Kd = prismatic ? kPrismaticKd : kRevoluteKd;
      dof.maxEffort = spec.effort > 0.0
                          ? spec.effort * (prismatic ? units::kNewton : units::kNewtonMetre)
                          : (prismatic ? kPrismaticEffort : kRevoluteEffort);
      dof.defaultValue = dof.clamp(0.0);
    }
  }

  // The MJCF joint behind chain joint j (matched by its place in the build order).
  int mjJointOf(const Joint&, const KinematicChain& chain, std::size_t j) const {
    const int global = chain.firstJoint + static_cast<int>(j);
    return global < static_cast<int>(build_order_.size()) ? build_order_[global] : -1;
  }

  fs::path file_;
  const LoadOptions& options_;
  std::deque<std::unique_ptr<xml::Document>> documents_;
  std::deque<fs::path> paths_;
  bool degrees_ = true;  // MuJoCo's default angle unit
  bool autolimits_ = true;
  std::string meshdir_;
  std::string eulerseq_ = "xyz";
  std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> classes_{
      {"main", {}}};
  std::map<std::string, MeshAsset> meshes_;
  std::map<fs::path, TriangleMesh> loaded_;
  std::vector<MjBody> bodies_;
  std::map<std::string, int> body_index_;
  std::vector<MjJoint> joints_;
  std::map<std::string, int> joint_index_;
  std::set<std::string> left_out_joint_names_;
  std::map<std::string, std::pair<Source, std::vector<std::pair<int, double>>>> tendons_;
  std::vector<std::pair<DofSpec, std::vector<std::pair<int, double>>>> actuators_;
  std::vector<DofSpec> dofs_;
  std::vector<Drive> drives_;
  std::map<int, double> frozen_;  // joints held at a value by an equality
  std::set<int> followers_;       // loop joints
  std::vector<double> loop_gaps_;
  std::vector<int> build_order_;
  std::vector<std::pair<int, int>> exclusions_;
};

}  // namespace

bool isMjcfFile(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".xml" && ext != ".mjcf") return false;
  try {
    return std::string_view(xml::Document(file).root().Name()) == "mujoco";
  } catch (const Error&) {
    return false;  // the reader that takes the file reports what is wrong with it
  }
}

std::shared_ptr<const RobotModel> loadMjcfFile(const fs::path& file, const LoadOptions& options) {
  return MjcfReader(file, options).read();
}

}  // namespace graspkit
