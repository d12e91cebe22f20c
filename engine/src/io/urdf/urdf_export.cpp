#include "graspkit/io/urdf/urdf_export.hpp"

// Writing a robot as URDF. A DH joint turns about (or slides along) the z axis of the frame
// before it and then carries its link by the constant rest of its DH transform, while a URDF
// joint turns about an axis through its child's origin. So each DH joint i becomes a movable
// joint onto an empty frame link on its axis, then a fixed joint that carries the rest
// (Tz(d) Tx(a) Rx(alpha), and the link's own Link::frame) to the link itself, whose URDF frame
// is then graspkit's link frame. A joint that carries no link of its own (the first joints of a
// Universal or Ball link) ends in an empty frame link the next joint hangs on.

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "graspkit/math/units.hpp"
#include "io/common/export_text.hpp"
#include "io/common/stl_bytes.hpp"

namespace graspkit {

namespace fs = std::filesystem;

namespace {

// "xyz=... rpy=..." of a transform (mm -> m). URDF's rpy is R = Rz(yaw) Ry(pitch) Rx(roll).
std::string originAttributes(const Transform& t) {
  const Matrix3& r = t.linear();
  const double pitch = std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0)));
  double roll, yaw;
  if (std::hypot(r(0, 0), r(1, 0)) > 1e-12) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {  // pitch at +-90 degrees: only roll -+ yaw is defined; take yaw = 0
    roll = std::atan2(-r(1, 2), r(1, 1));
    yaw = 0.0;
  }
  const Vector3 p = t.translation() / units::kMetre;
  return fmt::format("xyz=\"{} {} {}\" rpy=\"{} {} {}\"", io::exactNumber(p.x()),
                     io::exactNumber(p.y()), io::exactNumber(p.z()), io::exactNumber(roll),
                     io::exactNumber(pitch), io::exactNumber(yaw));
}

class UrdfWriter {
 public:
  UrdfWriter(const RobotModel& robot, const fs::path& folder) : robot_(robot), folder_(folder) {}

  fs::path write() {
    createOutputFolder(folder_ / "meshes");
    const std::string palm = name(robot_.palm ? robot_.palm->name : "", "palm");
    link(palm, robot_.palm.get());
    for (std::size_t c = 0; c < robot_.chains.size(); ++c) chain(static_cast<int>(c), palm);
    std::ostringstream text;
    text << "<?xml version=\"1.0\"?>\n";
    text << fmt::format("<!-- written by graspkit from {} -->\n",
                        io::xmlCommentText(robot_.file.filename().string()));
    text << fmt::format("<robot name=\"{}\">\n", io::xmlEscaped(robot_.name));
    // MuJoCo's URDF importer keeps only a mesh path's file name: its compiler extension says
    // where the meshes are (urdfdom ignores the element). Links stay bodies of their own, and
    // the empty frame links on the joint axes get MuJoCo's least mass (a milligram).
    text << "  <mujoco><compiler meshdir=\"meshes\" fusestatic=\"false\" "
            "discardvisual=\"false\" balanceinertia=\"true\" boundmass=\"1e-6\" "
            "boundinertia=\"1e-12\"/></mujoco>\n";
    text << links_.str();
    // DOF order is the order of the joints that mimic nothing: each DOF's first joint first.
    for (const std::string& joint : masters_) text << joint;
    text << joints_.str();
    text << "</robot>\n";
    const fs::path file = folder_ / (io::fileStem(robot_.name, "robot") + ".urdf");
    writeFileAtomically(file, text.str());
    return file;
  }

 private:
  // A unique URDF name, from the given one or the fallback.
  std::string name(const std::string& wanted, const std::string& fallback) {
    std::string base = wanted.empty() ? fallback : wanted;
    for (char& ch : base)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') ch = '_';
    std::string unique = base;
    for (int k = 2; !used_.insert(unique).second; ++k) unique = fmt::format("{}_{}", base, k);
    return unique;
  }

  void link(const std::string& link_name, const BodyModel* body) {
    links_ << fmt::format("  <link name=\"{}\">\n", link_name);
    if (body && body->mesh && !body->mesh->empty()) {
      const std::string mesh = fmt::format("meshes/{}.stl", link_name);
      writeFileAtomically(folder_ / mesh, io::stlBytes(*body->mesh));
      links_ << fmt::format(
          "    <visual><geometry><mesh filename=\"{0}\"/></geometry></visual>\n"
          "    <collision><geometry><mesh filename=\"{0}\"/></geometry></collision>\n",
          mesh);
    }
    if (body && body->mass > 0.0) {
      const Matrix3 inertia =
          body->inertia * body->mass / (units::kKilogram * units::kMetre * units::kMetre);
      Transform at = Transform::Identity();
      at.translation() = body->cog;
      links_ << fmt::format(
          "    <inertial><origin {}/><mass value=\"{}\"/><inertia ixx=\"{}\" ixy=\"{}\" "
          "ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial>\n",
          originAttributes(at), io::exactNumber(body->mass / units::kKilogram),
          io::exactNumber(inertia(0, 0)), io::exactNumber(inertia(0, 1)),
          io::exactNumber(inertia(0, 2)), io::exactNumber(inertia(1, 1)),
          io::exactNumber(inertia(1, 2)), io::exactNumber(inertia(2, 2)));
    }
    links_ << "  </link>\n";
  }

  void chain(int c, const std::string& palm) {
    const KinematicChain& chain = robot_.chains[c];
    std::string parent = palm;
    Transform carried = chain.base;  // from the parent's frame to the frame before the joint
    for (std::size_t j = 0; j < chain.joints.size(); ++j) {
      const Joint& joint = chain.joints[j];
      const bool prismatic = joint.type == JointType::Prismatic;
      const int global = chain.firstJoint + static_cast<int>(j);
      // On the axis: the constant part of the driven parameter.
      Transform to_axis = carried * Eigen::AngleAxisd(joint.theta, Vector3::UnitZ());
      if (prismatic) to_axis = to_axis * Eigen::Translation3d(0, 0, joint.d);
      const std::string axis_link = name(fmt::format("chain{}_joint{}", c, j), "joint");
      links_ << fmt::format("  <link name=\"{}\"/>\n", axis_link);
      movableJoint(global, joint, parent, axis_link, to_axis);
      // The rest of the DH transform, then the link (if this joint carries one).
      Transform rest = Transform::Identity();
      if (!prismatic) rest = rest * Eigen::Translation3d(0, 0, joint.d);
      rest = rest * Eigen::Translation3d(joint.a, 0, 0) *
             Eigen::AngleAxisd(joint.alpha, Vector3::UnitX());
      const Link* carried_link = nullptr;
      for (const Link& l : chain.links)
        if (l.lastJoint == static_cast<int>(j)) carried_link = &l;
      if (carried_link) {
        const std::string link_name = name(carried_link->name, fmt::format("chain{}_link", c));
        link(link_name, carried_link->body.get());
        fixedJoint(axis_link, link_name, rest * carried_link->frame);
        parent = link_name;
        carried = carried_link->frame.inverse();
      } else {
        parent = axis_link;
        carried = rest;
      }
    }
  }

  void movableJoint(int global, const Joint& joint, const std::string& parent,
                    const std::string& child, const Transform& origin) {
    const Dof& dof = robot_.dofs[joint.dof];
    const bool prismatic = joint.type == JointType::Prismatic;
    const double unit = prismatic ? units::kMetre : 1.0;
    const std::string joint_name = name(fmt::format("joint{}", global), "joint");
    const double effort = dof.maxEffort > 0.0 ? dof.maxEffort / (prismatic ? 1e6 : 1e9) : 0.0;
    std::string text = fmt::format(
        "  <joint name=\"{}\" type=\"{}\">\n    <parent link=\"{}\"/><child link=\"{}\"/>\n"
        "    <origin {}/><axis xyz=\"0 0 1\"/>\n"
        "    <limit lower=\"{}\" upper=\"{}\" effort=\"{}\" velocity=\"{}\"/>\n",
        joint_name, prismatic ? "prismatic" : "revolute", parent, child, originAttributes(origin),
        io::exactNumber(joint.min / unit), io::exactNumber(joint.max / unit),
        io::exactNumber(effort),
        io::exactNumber(std::abs(dof.defaultVelocity) > 0 ? std::abs(dof.defaultVelocity) / unit
                                                          : 1.0));
    const auto master = master_joint_.find(joint.dof);
    if (master == master_joint_.end()) {
      master_joint_[joint.dof] = {joint_name, joint.ratio};
      masters_.resize(std::max<std::size_t>(masters_.size(), joint.dof + 1));
      masters_[joint.dof] = text + "  </joint>\n";
      return;
    }
    // value = ratio * DOF = (ratio / master ratio) * master's value.
    text += fmt::format("    <mimic joint=\"{}\" multiplier=\"{}\" offset=\"0\"/>\n",
                        master->second.first, io::exactNumber(joint.ratio / master->second.second));
    joints_ << text << "  </joint>\n";
  }

  void fixedJoint(const std::string& parent, const std::string& child, const Transform& origin) {
    joints_ << fmt::format(
        "  <joint name=\"{}\" type=\"fixed\">\n    <parent link=\"{}\"/><child link=\"{}\"/>\n"
        "    <origin {}/>\n  </joint>\n",
        name(child + "_fixed", "fixed"), parent, child, originAttributes(origin));
  }

  const RobotModel& robot_;
  fs::path folder_;
  std::set<std::string> used_;
  std::ostringstream links_, joints_;
  std::vector<std::string> masters_;
  std::map<int, std::pair<std::string, double>> master_joint_;
};

}  // namespace

fs::path saveUrdf(const RobotModel& robot, const fs::path& folder) {
  for (const KinematicChain& chain : robot.chains)
    for (const Joint& joint : chain.joints)
      if (joint.ratio == 0.0)
        throw Error(
            fmt::format("robot '{}': a joint coupled with ratio 0 has no URDF form", robot.name));
  return UrdfWriter(robot, folder).write();
}

}  // namespace graspkit
