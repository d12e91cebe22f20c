#include "graspkit/io/urdf/urdf_file.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <urdf_parser/urdf_parser.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "geometry/primitive_meshes.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
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

// The most joints a hand's chains may hold, shared joints repeated (the robot limit).
constexpr std::size_t kMaxChainJoints = 4096;
constexpr double kLargestNumber = 1e6;
// Controller gains, and the effort where the URDF gives none: GraspIt!'s Barrett finger DOFs
// for revolute joints, graspkit's parallel_jaw for prismatic ones.
constexpr double kRevoluteKp = 1.0e11, kRevoluteKd = 1.0e7, kRevoluteEffort = 2.5e9;
constexpr double kPrismaticKp = 1.0e9, kPrismaticKd = 1.0e6, kPrismaticEffort = 1.0e8;

Transform poseTransform(const urdf::Pose& pose) {
  double x, y, z, w;
  pose.rotation.getQuaternion(x, y, z, w);
  Transform t = Transform::Identity();
  t.linear() = Quaternion(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = units::kMetre * Vector3(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

Vector3 vector(const urdf::Vector3& v) {
  return Vector3(v.x, v.y, v.z);
}

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

class UrdfReader {
 public:
  UrdfReader(const fs::path& file, const LoadOptions& options)
      : file_(file), options_(options), document_(file) {}

  std::shared_ptr<const RobotModel> read() {
    const XMLElement& root = document_.root();
    if (std::string_view(root.Name()) != "robot")
      throw Error(xml::at(file_, root), "the root element of a URDF file must be <robot>");
    indexElements(root);
    checkLinks();
    checkJoints();
    checkTree(root);
    parse(root);
    const std::string palm = palmLink(root);
    for (const auto& [link, material] : options_.urdfLinkMaterials)
      if (!link_elements_.count(link))
        throw Error(
            xml::at(file_, root),
            fmt::format("a material is given for link '{}', which the file does not have", link));
    auto robot = std::make_shared<RobotModel>();
    robot->file = file_;
    robot->name = model_->getName().empty() ? file_.stem().string() : model_->getName();
    robot->type = "Hand";
    robot->dbName = robot->name;
    robot->isHand = true;
    Registry& registry = options_.registry ? *options_.registry : Registry::global();
    robot->robotType = registry.robotType("Hand");
    robot->typeProvider = "URDF";
    robot->palmFile = palm;
    readDofs(*robot, palm);
    robot->palm = groupBody(palm, Transform::Identity(), palm);
    for (const auto& [member, frame] : rigidGroup(palm)) link_ref_[member] = LinkRef{};
    // Chains in the order their first links come in the file.
    std::vector<urdf::JointSharedPtr> firsts = childJoints(palm, true);
    std::stable_sort(firsts.begin(), firsts.end(), [&](const auto& a, const auto& b) {
      return link_order_.at(a->child_link_name) < link_order_.at(b->child_link_name);
    });
    // A finger tree that branches below a moving joint (a palm arch carrying two fingers) gives
    // one chain per path from the palm to a leaf; a joint on several paths is repeated in each,
    // driven by its DOF, and its link belongs to the first chain.
    for (const urdf::JointSharedPtr& joint : firsts)
      for (const std::vector<const urdf::Joint*>& path : pathsFrom(*joint)) readChain(path, *robot);
    if (robot->chains.empty())
      throw Error(xml::at(file_, *link_elements_.at(palm)),
                  fmt::format("no movable joint hangs on the palm '{}'", palm));
    finishDofs(*robot);
    robot->eigengrasps = identityEigengrasps(static_cast<int>(robot->dofs.size()));
    readSrdf(*robot);
    if (options_.switchOffInherentCollisions) disableInherentSelfCollisions(*robot);
    if (options_.inferClosingDirections)
      setClosingDirections(*robot, inferClosingDirections(*robot));
    // The hand setup's virtual contacts: the palm's and the fingertips' (virtual_contact.hpp).
    robot->virtualContacts = deriveFingertipContacts(Robot(robot));
    return robot;
  }

 private:
  // --- Checks on the XML, where line numbers are known -------------------------------------

  void indexElements(const XMLElement& root) {
    for (const XMLElement* e : xml::children(root, "link")) {
      const char* name = e->Attribute("name");
      if (!name || !*name) throw Error(xml::at(file_, *e), "a <link> needs a name");
      if (!link_elements_.emplace(name, e).second)
        throw Error(xml::at(file_, *e), fmt::format("a second link named '{}'", name));
      link_order_.emplace(name, static_cast<int>(link_order_.size()));
      // The robot limits, before anything is built from the file (a URDF is otherwise
      // unbounded: a 100,000-link chain would take minutes).
      if (link_order_.size() > static_cast<std::size_t>(kMaxRobotJoints))
        throw Error(xml::at(file_, *e),
                    fmt::format("more than {} links in one robot", kMaxRobotJoints));
    }
    for (const XMLElement* e : xml::children(root, "joint")) {
      const char* name = e->Attribute("name");
      if (!name || !*name) throw Error(xml::at(file_, *e), "a <joint> needs a name");
      if (!joint_elements_.emplace(name, e).second)
        throw Error(xml::at(file_, *e), fmt::format("a second joint named '{}'", name));
      joint_order_.push_back(name);
      if (joint_order_.size() > static_cast<std::size_t>(kMaxRobotJoints))
        throw Error(xml::at(file_, *e),
                    fmt::format("more than {} joints in one robot", kMaxRobotJoints));
    }
    if (link_elements_.empty()) throw Error(xml::at(file_, root), "a URDF robot needs a <link>");
  }

  // Numbers in an attribute: all finite, `count` of them.
  std::vector<double> finiteNumbers(const XMLElement& element, const char* attribute,
                                    std::size_t count) {
    const char* text = element.Attribute(attribute);
    if (!text) return {};
    std::vector<double> values;
    for (std::string_view token : xml::tokens(text)) {
      const auto value = xml::toDouble(token);
      // Past a million (metres, kilograms, newtons) a number is a typo or an attack, and its
      // squares overflow: an axis 1e308 1e308 0 has no direction in doubles.
      if (!value || !std::isfinite(*value) || std::abs(*value) > kLargestNumber)
        throw Error(xml::at(file_, element),
                    fmt::format("{}=\"{}\": '{}' is not a finite number within +-1e6", attribute,
                                text, token));
      values.push_back(*value);
    }
    if (values.size() != count)
      throw Error(xml::at(file_, element),
                  fmt::format("{}=\"{}\" needs {} numbers", attribute, text, count));
    return values;
  }

  // What urdfdom would read quietly (it drops a NaN mass or size and loads the rest): every
  // number of a link checked finite and in range, masses not negative, sizes positive.
  void checkLinks() {
    for (const auto& [name, e] : link_elements_) {
      if (const XMLElement* inertial = e->FirstChildElement("inertial")) {
        if (const XMLElement* origin = inertial->FirstChildElement("origin")) {
          finiteNumbers(*origin, "xyz", 3);
          finiteNumbers(*origin, "rpy", 3);
        }
        if (const XMLElement* mass = inertial->FirstChildElement("mass")) {
          const std::vector<double> m = finiteNumbers(*mass, "value", 1);
          if (!m.empty() && m[0] < 0.0)
            throw Error(xml::at(file_, *mass), fmt::format("link '{}': a negative mass", name));
          // URDF's way to say "massless" (a frame, a sensor): it adds nothing to the body it is
          // fixed to, and a link of its own then takes GraspIt!'s default mass. Said, not silent.
          if (!m.empty() && m[0] == 0.0)
            warn(WarningKind::Mass, xml::at(file_, *mass),
                 fmt::format("link '{}': mass 0; a link with no mass of its own takes GraspIt!'s "
                             "default {} g",
                             name, kDefaultMass));
        }
        if (const XMLElement* inertia = inertial->FirstChildElement("inertia"))
          for (const char* a : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"})
            finiteNumbers(*inertia, a, 1);
      }
      for (const char* part : {"visual", "collision"}) {
        for (const XMLElement* p = e->FirstChildElement(part); p; p = p->NextSiblingElement(part)) {
          if (const XMLElement* origin = p->FirstChildElement("origin")) {
            finiteNumbers(*origin, "xyz", 3);
            finiteNumbers(*origin, "rpy", 3);
          }
          const XMLElement* geometry = p->FirstChildElement("geometry");
          const XMLElement* shape = geometry ? geometry->FirstChildElement() : nullptr;
          if (!shape) continue;
          const std::string_view kind = shape->Name();
          std::vector<double> sizes;
          if (kind == "box") sizes = finiteNumbers(*shape, "size", 3);
          if (kind == "sphere") sizes = finiteNumbers(*shape, "radius", 1);
          if (kind == "cylinder") {
            sizes = finiteNumbers(*shape, "radius", 1);
            const std::vector<double> length = finiteNumbers(*shape, "length", 1);
            sizes.insert(sizes.end(), length.begin(), length.end());
          }
          if (kind == "mesh") {
            for (const double k : finiteNumbers(*shape, "scale", 3))
              if (k == 0.0)
                throw Error(xml::at(file_, *shape), fmt::format("link '{}': a zero scale", name));
          }
          for (const double size : sizes)
            if (!(size > 0.0))
              throw Error(xml::at(file_, *shape),
                          fmt::format("link '{}': a {}'s size must be positive", name, kind));
        }
      }
    }
  }

  void checkJoints() {
    for (const auto& [name, e] : joint_elements_) {
      const char* type = e->Attribute("type");
      const std::string_view t = type ? type : "";
      if (t == "floating" || t == "planar")
        throw Error(xml::at(file_, *e),
                    fmt::format("joint '{}': {} joints are not supported (a hand's joints are "
                                "revolute, continuous, prismatic or fixed)",
                                name, t));
      if (t != "revolute" && t != "continuous" && t != "prismatic" && t != "fixed")
        throw Error(xml::at(file_, *e), fmt::format("joint '{}': unknown type '{}'", name, t));
      for (const char* end : {"parent", "child"}) {
        const XMLElement* link = e->FirstChildElement(end);
        const char* link_name = link ? link->Attribute("link") : nullptr;
        if (!link_name)
          throw Error(xml::at(file_, *e), fmt::format("joint '{}' needs <{} link=...>", name, end));
        if (!link_elements_.count(link_name))
          throw Error(xml::at(file_, *link),
                      fmt::format("joint '{}': no link named '{}'", name, link_name));
      }
      if (const XMLElement* origin = e->FirstChildElement("origin")) {
        finiteNumbers(*origin, "xyz", 3);
        finiteNumbers(*origin, "rpy", 3);
      }
      const XMLElement* axis = e->FirstChildElement("axis");
      if (axis) {
        const std::vector<double> xyz = finiteNumbers(*axis, "xyz", 3);
        if (!xyz.empty() && Vector3(xyz[0], xyz[1], xyz[2]).norm() < 1e-9)
          throw Error(xml::at(file_, *axis), fmt::format("joint '{}': the axis is zero", name));
      }
      const XMLElement* limit = e->FirstChildElement("limit");
      if ((t == "revolute" || t == "prismatic") && !limit)
        throw Error(xml::at(file_, *e),
                    fmt::format("joint '{}': a {} joint needs <limit>", name, t));
      if (limit) {
        for (const char* attribute : {"lower", "upper", "effort", "velocity"})
          finiteNumbers(*limit, attribute, 1);
        for (const char* attribute : {"effort", "velocity"})
          if (!limit->Attribute(attribute))
            throw Error(xml::at(file_, *limit),
                        fmt::format("joint '{}': <limit> needs {}=", name, attribute));
        const double lower = limit->DoubleAttribute("lower", 0.0);
        const double upper = limit->DoubleAttribute("upper", 0.0);
        if (t != "continuous" && lower > upper)
          throw Error(xml::at(file_, *limit),
                      fmt::format("joint '{}': lower limit {} above upper {}", name, lower, upper));
      }
      // URDF lets a movable joint leave its axis out and take (1, 0, 0); a hand file that does
      // so has more often lost its axis than meant that one, so it is asked for.
      if (t != "fixed" && (!axis || !axis->Attribute("xyz")))
        throw Error(xml::at(file_, axis ? *axis : *e),
                    fmt::format("joint '{}': a {} joint needs <axis xyz=...> (URDF's default is "
                                "\"1 0 0\"; write it if that is the axis meant)",
                                name, t));
      if (const XMLElement* mimic = e->FirstChildElement("mimic")) {
        const char* target = mimic->Attribute("joint");
        if (!target || !joint_elements_.count(target))
          throw Error(xml::at(file_, *mimic),
                      fmt::format("joint '{}' mimics '{}', which is not a joint of the file", name,
                                  target ? target : ""));
        finiteNumbers(*mimic, "multiplier", 1);
        finiteNumbers(*mimic, "offset", 1);
      }
    }
    // Mimic chains end at a joint that mimics nothing.
    for (const auto& [name, e] : joint_elements_) {
      std::set<std::string> seen{name};
      for (std::string at = name;;) {
        const XMLElement* mimic = joint_elements_.at(at)->FirstChildElement("mimic");
        if (!mimic) break;
        at = mimic->Attribute("joint");
        if (!seen.insert(at).second)
          throw Error(xml::at(file_, *mimic),
                      fmt::format("joint '{}': its mimic joints form a loop", name));
      }
    }
  }

  // One parent per link, and no cycle: a tree.
  void checkTree(const XMLElement& root) {
    std::map<std::string, std::string> parent_joint;
    for (const auto& name : joint_order_) {
      const XMLElement& e = *joint_elements_.at(name);
      const std::string child = e.FirstChildElement("child")->Attribute("link");
      const auto [it, fresh] = parent_joint.emplace(child, name);
      if (!fresh)
        throw Error(xml::at(file_, e), fmt::format("link '{}' is the child of joints '{}' and '{}'",
                                                   child, it->second, name));
    }
    for (const auto& [link, joint] : parent_joint) {
      std::set<std::string> seen{link};
      for (auto at = parent_joint.find(link); at != parent_joint.end();) {
        const std::string parent =
            joint_elements_.at(at->second)->FirstChildElement("parent")->Attribute("link");
        if (!seen.insert(parent).second)
          throw Error(
              xml::at(file_, *joint_elements_.at(at->second)),
              fmt::format("joint '{}' closes a cycle through link '{}'", at->second, parent));
        at = parent_joint.find(parent);
      }
    }
    std::vector<std::string> roots;
    for (const auto& [name, e] : link_elements_)
      if (!parent_joint.count(name)) roots.push_back(name);
    if (roots.size() > 1)
      throw Error(xml::at(file_, root),
                  fmt::format("the links form {} trees (roots '{}' and '{}'): a robot is one tree",
                              roots.size(), roots[0], roots[1]));
  }

  void parse(const XMLElement& root) {
    std::ifstream in(file_, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    try {
      model_ = urdf::parseURDF(text.str());
    } catch (const std::exception& e) {  // urdfdom throws for numbers it cannot read
      throw Error(xml::at(file_, root),
                  fmt::format("urdfdom could not read the robot: {}", e.what()));
    }
    if (!model_)
      throw Error(xml::at(file_, root),
                  "urdfdom could not read the robot (its messages above say why)");
  }

  std::string palmLink(const XMLElement& root) const {
    if (options_.urdfPalm.empty()) return model_->getRoot()->name;
    if (!link_elements_.count(options_.urdfPalm))
      throw Error(xml::at(file_, root),
                  fmt::format("palm '{}': the file has no link of that name", options_.urdfPalm));
    return options_.urdfPalm;
  }

  // --- The model ------------------------------------------------------------------------------

  // A joint urdfdom read; an element urdfdom dropped (its reading differs from tinyxml2's, as
  // for a name with odd bytes) is an error at the element, not a crash.
  const urdf::JointSharedPtr& jointPtr(const std::string& name) const {
    const auto found = model_->joints_.find(name);
    if (found == model_->joints_.end() || !found->second)
      throw Error(xml::at(file_, *joint_elements_.at(name)),
                  fmt::format("urdfdom did not read joint '{}'", name));
    return found->second;
  }
  const urdf::Joint& joint(const std::string& name) const { return *jointPtr(name); }
  urdf::LinkConstSharedPtr urdfLink(const std::string& name) const {
    urdf::LinkConstSharedPtr l = model_->getLink(name);
    if (!l) {
      const auto e = link_elements_.find(name);
      if (e == link_elements_.end())
        throw Error(xml::at(file_, document_.root()), fmt::format("no link named '{}'", name));
      throw Error(xml::at(file_, *e->second), fmt::format("urdfdom did not read link '{}'", name));
    }
    return l;
  }

  // The joints whose parent is `link` (file order), movable or fixed.
  std::vector<urdf::JointSharedPtr> jointsBelow(const std::string& link) const {
    if (below_.empty()) {  // indexed once: a scan per link made loading quadratic
      for (const std::string& name : joint_order_) {
        const urdf::JointSharedPtr& j = jointPtr(name);
        below_[j->parent_link_name].push_back(j);
      }
    }
    const auto found = below_.find(link);
    return found == below_.end() ? std::vector<urdf::JointSharedPtr>{} : found->second;
  }

  // The links rigidly attached to `link` by fixed joints (itself included), with their frames
  // in `link`'s frame.
  std::vector<std::pair<std::string, Transform>> rigidGroup(const std::string& link) const {
    std::vector<std::pair<std::string, Transform>> group{{link, Transform::Identity()}};
    for (std::size_t i = 0; i < group.size(); ++i) {
      for (const urdf::JointSharedPtr& j : jointsBelow(group[i].first)) {
        if (j->type != urdf::Joint::FIXED) continue;
        group.emplace_back(j->child_link_name,
                           group[i].second * poseTransform(j->parent_to_joint_origin_transform));
      }
    }
    return group;
  }

  // The movable joints hung on `link`'s rigid group, with the frame of each joint's parent link
  // in `link`'s frame.
  std::vector<urdf::JointSharedPtr> childJoints(const std::string& link, bool /*palm*/) const {
    std::vector<urdf::JointSharedPtr> out;
    for (const auto& [member, frame] : rigidGroup(link))
      for (const urdf::JointSharedPtr& j : jointsBelow(member))
        if (isMovable(*j)) out.push_back(j);
    return out;
  }

  Transform memberFrame(const std::string& group_link, const std::string& member) const {
    for (const auto& [name, frame] : rigidGroup(group_link))
      if (name == member) return frame;
    return Transform::Identity();
  }

  // The joints below `palm`, in file order.
  std::set<std::string> jointsUnder(const std::string& palm) const {
    std::set<std::string> out;
    std::vector<std::string> links{palm};
    while (!links.empty()) {
      const std::string link = links.back();
      links.pop_back();
      for (const urdf::JointSharedPtr& j : jointsBelow(link)) {
        out.insert(j->name);
        links.push_back(j->child_link_name);
      }
    }
    return out;
  }

  void readDofs(RobotModel& robot, const std::string& palm) {
    const std::set<std::string> under = jointsUnder(palm);
    for (const std::string& name : joint_order_) {
      const urdf::Joint& j = joint(name);
      if (!isMovable(j) || j.mimic || !under.count(name)) continue;
      if (robot.dofs.size() == static_cast<std::size_t>(kMaxRobotDofs))
        throw Error(xml::at(file_, *joint_elements_.at(name)),
                    fmt::format("more than {} DOFs in one robot", kMaxRobotDofs));
      dof_of_[name] = static_cast<int>(robot.dofs.size());
      Dof dof;
      dof.type = DofType::Rigid;
      // Closing speeds as GraspIt!'s hands give them: the Barrett's 1 rad/s, parallel_jaw's
      // 10 mm/s.
      dof.defaultVelocity = j.type == urdf::Joint::PRISMATIC ? 10.0 : 1.0;
      const bool prismatic = j.type == urdf::Joint::PRISMATIC;
      dof.Kp = prismatic ? kPrismaticKp : kRevoluteKp;
      dof.Kd = prismatic ? kPrismaticKd : kRevoluteKd;
      const double effort = j.limits ? j.limits->effort : 0.0;
      dof.maxEffort = effort > 0.0 ? effort * (prismatic ? units::kNewton : units::kNewtonMetre)
                                   : (prismatic ? kPrismaticEffort : kRevoluteEffort);
      robot.dofs.push_back(dof);
    }
  }

  // A mimic joint's DOF, multiplier and offset, following mimics of mimics.
  struct Drive {
    int dof = 0;
    double ratio = 1.0;
    double offset = 0.0;  // URDF units
  };
  Drive drive(const urdf::Joint& j) const {
    if (!j.mimic) {
      const auto dof = dof_of_.find(j.name);
      if (dof == dof_of_.end())
        throw Error(xml::at(file_, *joint_elements_.at(j.name)),
                    fmt::format("joint '{}' is mimicked below the palm but lies above it", j.name));
      return {dof->second, 1.0, 0.0};
    }
    const Drive target = drive(joint(j.mimic->joint_name));
    return {target.dof, j.mimic->multiplier * target.ratio,
            j.mimic->multiplier * target.offset + j.mimic->offset};
  }

  // Every path of movable joints from `first` down to a leaf, in file order.
  std::vector<std::vector<const urdf::Joint*>> pathsFrom(const urdf::Joint& first) const {
    std::vector<std::vector<const urdf::Joint*>> out;
    std::vector<const urdf::Joint*> path;
    std::size_t joints = 0;
    std::function<void(const urdf::Joint*)> walk = [&](const urdf::Joint* j) {
      path.push_back(j);
      const std::vector<urdf::JointSharedPtr> next = childJoints(j->child_link_name, false);
      if (next.empty()) {
        joints += path.size();
        if (joints > kMaxChainJoints)
          throw Error(xml::at(file_, *joint_elements_.at(first.name)),
                      fmt::format("the tree below joint '{}' repeats its shared joints into more "
                                  "than {} chain joints",
                                  first.name, kMaxChainJoints));
        out.push_back(path);
      }
      for (const urdf::JointSharedPtr& n : next) walk(n.get());
      path.pop_back();
    };
    walk(&first);
    return out;
  }

  void readChain(const std::vector<const urdf::Joint*>& path, RobotModel& robot) {
    // The chain's joints, each with its parent link's frame at the zero joint vector (palm
    // frame) and its child link's.
    std::vector<const urdf::Joint*> joints;
    std::vector<Transform> child_frames;  // URDF frame of each joint's child link, q = 0
    std::vector<Vector3> points, axes;
    Transform group_frame = Transform::Identity();  // the palm's, then each link group's
    std::string group = robot.palmFile;
    for (const urdf::Joint* j : path) {
      const Transform parent = group_frame * memberFrame(group, j->parent_link_name);
      const Transform at_joint = parent * poseTransform(j->parent_to_joint_origin_transform);
      joints.push_back(j);
      child_frames.push_back(at_joint);
      points.push_back(at_joint.translation());
      axes.push_back((at_joint.linear() * vector(j->axis)).normalized());
      group = j->child_link_name;
      group_frame = at_joint;
    }

    KinematicChain chain;
    chain.firstJoint = robot.jointCount();
    int consumed = 0;  // joints since the last link
    Transform before = Transform::Identity();
    before.linear() = io::frameWithZ(axes[0], Vector3::UnitX());
    before.translation() = points[0];
    chain.base = before;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const urdf::Joint& j = *joints[i];
      Joint dh;
      dh.type = j.type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
      Transform after;
      if (i + 1 < joints.size()) {
        io::denavitHartenbergTo(before, points[i + 1], axes[i + 1], dh, after);
      } else {
        after = before * dh.transform(0.0);
      }
      const Drive d = drive(j);
      dh.dof = d.dof;
      dh.ratio = d.ratio;
      const double unit = dh.type == JointType::Prismatic ? units::kMetre : 1.0;
      // URDF: q = ratio * DOF + offset; graspkit: value = ratio * DOF, the offset in the DH
      // parameter the joint drives.
      (dh.type == JointType::Prismatic ? dh.d : dh.theta) += d.offset * unit;
      if (j.type == urdf::Joint::CONTINUOUS) {
        dh.min = -M_PI;
        dh.max = M_PI;
      } else {
        dh.min = (j.limits->lower - d.offset) * unit;
        dh.max = (j.limits->upper - d.offset) * unit;
      }
      if (j.dynamics) {
        dh.viscousFriction =
            j.dynamics->damping * (dh.type == JointType::Prismatic ? units::kNewton / units::kMetre
                                                                   : units::kNewtonMetre);
        dh.coulombFriction =
            j.dynamics->friction *
            (dh.type == JointType::Prismatic ? units::kNewton : units::kNewtonMetre);
      }
      if (j.mimic) mimics_[chain.firstJoint + static_cast<int>(chain.joints.size())] = j.name;
      chain.joints.push_back(dh);
      before = after;
      // The link rides on the frame after the joint and keeps its URDF frame, a constant
      // transform from it (both turn with the joint).
      ++consumed;
      const std::string carrier = carrierLink(j.child_link_name);
      // An empty frame, or a link an earlier chain of the same tree holds (a shared joint's):
      // the next link takes this joint too.
      if (carrier.empty() || !placed_.insert(carrier).second) continue;
      const Transform carrier_frame = memberFrame(j.child_link_name, carrier);
      Link link;
      link.name = carrier;
      link.file = carrier;
      link.jointType = consumed == 2                     ? DynamicJointType::Universal
                       : consumed >= 3                   ? DynamicJointType::Ball
                       : dh.type == JointType::Prismatic ? DynamicJointType::Prismatic
                                                         : DynamicJointType::Revolute;
      link.lastJoint = static_cast<int>(i);
      link.frame = after.inverse() * child_frames[i] * carrier_frame;
      link.body = groupBody(j.child_link_name, carrier_frame.inverse(), carrier);
      for (const auto& [member, frame] : rigidGroup(j.child_link_name))
        link_ref_[member] =
            LinkRef{static_cast<int>(robot.chains.size()), static_cast<int>(chain.links.size())};
      chain.links.push_back(std::move(link));
      consumed = 0;
    }
    robot.chains.push_back(std::move(chain));
  }

  // Whether a link has geometry or mass of its own.
  bool hasBody(const std::string& link) const {
    const urdf::LinkConstSharedPtr l = urdfLink(link);
    return !l->collision_array.empty() || !l->visual_array.empty() ||
           (l->inertial && l->inertial->mass > 0.0);
  }

  // The link whose frame a rigid group takes: its first link, unless that is an empty frame;
  // then the first link fixed to it that has a body. Empty when none has.
  std::string carrierLink(const std::string& group) const {
    for (const auto& [member, frame] : rigidGroup(group))
      if (hasBody(member)) return member;
    return "";
  }

  void finishDofs(RobotModel& robot) {
    followMimicLimitsAsRos(robot);
    model::gatherDofJoints(robot);
    for (std::size_t d = 0; d < robot.dofs.size(); ++d) {
      Dof& dof = robot.dofs[d];
      if (dof.joints.empty()) {  // a joint below a link the palm does not reach
        dof.min = dof.max = 0.0;
      } else if (dof.min > dof.max) {
        throw Error(xml::at(file_, document_.root()),
                    fmt::format("DOF {} has an empty range: the limits of the joints that "
                                "mimic each other do not overlap",
                                d));
      }
      dof.defaultValue = dof.clamp(0.0);
    }
  }

  // SRDF <disable_collisions link1 link2 reason>: from LoadOptions::srdf, else the .srdf beside
  // the URDF. Links the hand leaves out (above the palm) are skipped; a name the URDF does not
  // have is an error.
  void readSrdf(RobotModel& robot) {
    fs::path srdf = options_.srdf;
    if (srdf.empty()) {
      fs::path beside = file_;
      beside.replace_extension(".srdf");
      std::error_code ec;
      if (!inputFileFound(beside) || !fs::is_regular_file(beside, ec)) return;
      srdf = beside;
    }
    const xml::Document doc(srdf);
    if (std::string_view(doc.root().Name()) != "robot")
      throw Error(xml::at(srdf, doc.root()), "the root element of an SRDF file must be <robot>");
    for (const XMLElement* e : xml::children(doc.root(), "disable_collisions")) {
      const char* names[2] = {e->Attribute("link1"), e->Attribute("link2")};
      std::optional<LinkRef> refs[2];
      for (int k = 0; k < 2; ++k) {
        if (!names[k]) throw Error(xml::at(srdf, *e), "<disable_collisions> needs link1 and link2");
        if (!link_elements_.count(names[k]))
          throw Error(xml::at(srdf, *e), fmt::format("link '{}' is not a link of {}", names[k],
                                                     file_.filename().string()));
        const auto ref = link_ref_.find(names[k]);
        if (ref != link_ref_.end()) refs[k] = ref->second;
      }
      if (!refs[0] || !refs[1] || *refs[0] == *refs[1]) continue;
      const char* reason = e->Attribute("reason");
      robot.disabledCollisions.push_back(
          {*refs[0], *refs[1],
           fmt::format("SRDF <disable_collisions> ({})", reason ? reason : "")});
    }
  }

  // ROS takes a mimic joint's value from its joint and ignores the mimic's own limits: here the
  // DOF's range is its own joint's, and a mimic's limits widen to what that range asks, with a
  // warning naming the joint where they are passed (they never collapse the DOF).
  void followMimicLimitsAsRos(RobotModel& robot) {
    std::vector<std::pair<double, double>> range(
        robot.dofs.size(),
        {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()});
    for (const KinematicChain& chain : robot.chains) {
      for (std::size_t i = 0; i < chain.joints.size(); ++i) {
        const Joint& joint = chain.joints[i];
        if (mimics_.count(chain.firstJoint + static_cast<int>(i))) continue;
        double lo = joint.min / joint.ratio, hi = joint.max / joint.ratio;
        if (lo > hi) std::swap(lo, hi);
        range[joint.dof].first = std::max(range[joint.dof].first, lo);
        range[joint.dof].second = std::min(range[joint.dof].second, hi);
      }
    }
    for (KinematicChain& chain : robot.chains) {
      for (std::size_t i = 0; i < chain.joints.size(); ++i) {
        const auto mimic = mimics_.find(chain.firstJoint + static_cast<int>(i));
        if (mimic == mimics_.end()) continue;
        Joint& joint = chain.joints[i];
        const auto [lo, hi] = range[joint.dof];
        if (!std::isfinite(lo) || !std::isfinite(hi)) continue;
        double a = joint.ratio * lo, b = joint.ratio * hi;
        if (a > b) std::swap(a, b);
        constexpr double kSlack = 1e-9;
        if (a >= joint.min - kSlack && b <= joint.max + kSlack) continue;
        const double unit = joint.type == JointType::Prismatic ? units::kMetre : 1.0;
        warn(WarningKind::Robot, xml::at(file_, *joint_elements_.at(mimic->second)),
             fmt::format("mimic joint '{}' is driven to [{:.6g}, {:.6g}], past its own limits "
                         "[{:.6g}, {:.6g}]; as in ROS, its limits do not narrow DOF {}",
                         mimic->second, a / unit, b / unit, joint.min / unit, joint.max / unit,
                         joint.dof));
        joint.min = std::min(joint.min, a);
        joint.max = std::max(joint.max, b);
      }
    }
  }

  // --- Bodies ---------------------------------------------------------------------------------

  // The body of `link` and the links fixed to it, in the frame `to_body` * (link frame).
  std::shared_ptr<const BodyModel> groupBody(const std::string& link, const Transform& to_body,
                                             const std::string& name) {
    auto body = std::make_shared<BodyModel>();
    body->name = name;
    body->file = file_;
    const auto own = options_.urdfLinkMaterials.find(name);
    body->material = own != options_.urdfLinkMaterials.end() ? own->second : options_.urdfMaterial;
    TriangleMesh mesh;
    double mass = 0.0;
    Vector3 moment = Vector3::Zero();   // sum of m * c
    Matrix3 inertia = Matrix3::Zero();  // about the body origin, g mm^2
    for (const auto& [member, frame] : rigidGroup(link)) {
      const Transform placed = to_body * frame;
      appendGeometry(member, placed, mesh, *body);
      const urdf::LinkConstSharedPtr l = urdfLink(member);
      if (!l->inertial || l->inertial->mass <= 0.0) continue;
      const urdf::Inertial& in = *l->inertial;
      const Transform at = placed * poseTransform(in.origin);
      const double m = in.mass * units::kKilogram;
      Matrix3 local;
      local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      local *= units::kKilogram * units::kMetre * units::kMetre;  // kg m^2 -> g mm^2
      const Vector3 c = at.translation();
      // Parallel axes: about the body origin.
      inertia += at.linear() * local * at.linear().transpose() +
                 m * (c.squaredNorm() * Matrix3::Identity() - c * c.transpose());
      mass += m;
      moment += m * c;
    }
    body->mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    io::setLinkMassProperties(*body, mass, moment, inertia);
    return body;
  }

  void appendGeometry(const std::string& link, const Transform& placed, TriangleMesh& mesh,
                      BodyModel& body) {
    const urdf::LinkConstSharedPtr l = urdfLink(link);
    std::vector<std::pair<urdf::GeometrySharedPtr, urdf::Pose>> shapes;
    for (const auto& c : l->collision_array)
      if (c && c->geometry) shapes.emplace_back(c->geometry, c->origin);
    if (shapes.empty()) {
      for (const auto& v : l->visual_array)
        if (v && v->geometry) shapes.emplace_back(v->geometry, v->origin);
    }
    for (const auto& [geometry, origin] : shapes) {
      TriangleMesh part = shapeMesh(link, *geometry, body);
      transformMesh(part, Eigen::Affine3d((placed * poseTransform(origin)).matrix()));
      const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
      for (const auto& t : part.triangles)
        mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }

  TriangleMesh shapeMesh(const std::string& link, const urdf::Geometry& geometry, BodyModel& body) {
    const XMLElement& where = *link_elements_.at(link);
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(geometry);
        return geometry::boxMesh(units::kMetre * vector(box.dim));
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(geometry);
        return geometry::cylinderMesh(units::kMetre * c.radius, units::kMetre * c.length);
      }
      case urdf::Geometry::SPHERE:
        return geometry::sphereMesh(units::kMetre *
                                    static_cast<const urdf::Sphere&>(geometry).radius);
      case urdf::Geometry::MESH:
        break;
    }
    const auto& m = static_cast<const urdf::Mesh&>(geometry);
    const fs::path path = meshPath(where, m.filename);
    TriangleMesh mesh;
    try {
      mesh = loadMesh(path);
    } catch (const Error& e) {
      throw Error(xml::at(file_, where), fmt::format("link '{}': {}", link, e.what()));
    }
    if (body.geometryFile.empty()) body.geometryFile = path;
    const Vector3 scale = units::kMetre * vector(m.scale);
    Eigen::Affine3d scaling = Eigen::Affine3d::Identity();
    scaling.linear() = scale.asDiagonal();
    transformMesh(mesh, scaling);
    return mesh;
  }

  // Where a URDF mesh filename points: package://NAME/REST in a package folder, file://PATH,
  // or a path relative to the URDF's folder.
  fs::path meshPath(const XMLElement& where, const std::string& filename) const {
    constexpr std::string_view kPackage = "package://", kFile = "file://";
    if (filename.rfind(kFile, 0) == 0) return existing(where, filename.substr(kFile.size()));
    if (filename.rfind(kPackage, 0) != 0) return existing(where, file_.parent_path() / filename);
    const std::string rest = filename.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    std::vector<fs::path> candidates;
    for (const fs::path& folder : options_.packagePaths) {
      candidates.push_back(folder / package / inside);
      if (folder.filename() == package) candidates.push_back(folder / inside);
    }
    for (fs::path up = fs::absolute(file_).parent_path();; up = up.parent_path()) {
      if (up.filename() == package) candidates.push_back(up / inside);
      candidates.push_back(up / package / inside);
      if (up == up.parent_path()) break;
    }
    std::error_code ec;
    for (const fs::path& candidate : candidates)
      if (inputFileFound(candidate) && fs::is_regular_file(candidate, ec)) return candidate;
    throw Error(xml::at(file_, where),
                fmt::format("mesh '{}': package '{}' not found (add its folder with "
                            "--package-path)",
                            filename, package));
  }

  fs::path existing(const XMLElement& where, const fs::path& path) const {
    // The read gate's check, so that a refused mesh tells nothing, not even whether it exists.
    return xml::locatedAt(file_, where, [&] {
      checkInputFile(path);
      return path;
    });
  }

  fs::path file_;
  const LoadOptions& options_;
  xml::Document document_;
  std::map<std::string, const XMLElement*> link_elements_;
  std::map<std::string, int> link_order_;
  std::map<std::string, const XMLElement*> joint_elements_;
  std::vector<std::string> joint_order_;
  urdf::ModelInterfaceSharedPtr model_;
  std::map<std::string, int> dof_of_;
  std::map<int, std::string> mimics_;        // robot-wide joint index -> name, mimic joints
  std::map<std::string, LinkRef> link_ref_;  // URDF link -> the graspkit link it is part of
  std::set<std::string> placed_;             // links already given to a chain
  mutable std::map<std::string, std::vector<urdf::JointSharedPtr>> below_;  // parent -> joints
};

}  // namespace

bool isUrdfFile(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".urdf";
}

std::shared_ptr<const RobotModel> loadUrdfFile(const fs::path& file, const LoadOptions& options) {
  return UrdfReader(file, options).read();
}

}  // namespace graspkit
