#include "graspkit/io/mjcf/mjcf_export.hpp"

// Writing a robot as MJCF for MuJoCo. MJCF places a joint's axis anywhere in its body's frame,
// so a DH joint needs no extra frame: each link is a body at its frame (relative to the link
// before, at the zero joint vector) with a hinge or slide joint on the axis of the DH frame
// before it. A joint that carries no link of its own (the first joints of a Universal or Ball
// link) gets a body of its own with a milligram of mass, which MuJoCo needs on anything that
// moves. Coupled joints follow their DOF's first joint through joint equality constraints.

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/math/units.hpp"
#include "io/common/export_text.hpp"
#include "io/common/stl_bytes.hpp"

namespace graspkit {

namespace fs = std::filesystem;

namespace {

constexpr double kPlaceholderMass = 1e-6;  // kg, for a body that only carries a joint

std::string placement(const Transform& t) {
  const Vector3 p = t.translation() / units::kMetre;
  const Quaternion q(t.linear());
  return fmt::format("pos=\"{} {} {}\" quat=\"{} {} {} {}\"", io::exactNumber(p.x()),
                     io::exactNumber(p.y()), io::exactNumber(p.z()), io::exactNumber(q.w()),
                     io::exactNumber(q.x()), io::exactNumber(q.y()), io::exactNumber(q.z()));
}

class MjcfWriter {
 public:
  MjcfWriter(const RobotModel& robot, const fs::path& folder) : robot_(robot), folder_(folder) {}

  fs::path write() {
    createOutputFolder(folder_ / "meshes");
    used_.insert("palm");
    body_ << "    <body name=\"palm\" pos=\"0 0 0\">\n";
    contents("palm", robot_.palm.get(), 6);
    for (std::size_t c = 0; c < robot_.chains.size(); ++c) chain(static_cast<int>(c));
    body_ << "    </body>\n";
    std::ostringstream text;
    text << fmt::format("<!-- written by graspkit from {} -->\n",
                        io::xmlCommentText(robot_.file.filename().string()));
    text << fmt::format("<mujoco model=\"{}\">\n", io::xmlEscaped(robot_.name));
    text << "  <compiler angle=\"radian\" meshdir=\"meshes\" inertiafromgeom=\"false\"/>\n";
    text << "  <asset>\n" << assets_.str() << "  </asset>\n";
    text << "  <worldbody>\n" << body_.str() << "  </worldbody>\n";
    const std::string excludes = exclusions();
    if (!excludes.empty()) text << "  <contact>\n" << excludes << "  </contact>\n";
    if (!equalities_.str().empty())
      text << "  <equality>\n" << equalities_.str() << "  </equality>\n";
    text << actuators();
    text << "</mujoco>\n";
    const fs::path file = folder_ / (io::fileStem(robot_.name, "robot") + ".xml");
    writeFileAtomically(file, text.str());
    return file;
  }

 private:
  std::string name(const std::string& wanted) {
    std::string base = wanted;
    for (char& ch : base)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') ch = '_';
    std::string unique = base;
    for (int k = 2; !used_.insert(unique).second; ++k) unique = fmt::format("{}_{}", base, k);
    return unique;
  }

  // A body's mesh and inertia (MuJoCo's inertia is about the CoG, in kg m^2).
  void contents(const std::string& body_name, const BodyModel* body, int indent) {
    const std::string pad(indent, ' ');
    if (body && body->mesh && !body->mesh->empty()) {
      const std::string mesh = name(body_name + "_mesh");
      writeFileAtomically(folder_ / "meshes" / (mesh + ".stl"), io::stlBytes(*body->mesh));
      assets_ << fmt::format("    <mesh name=\"{0}\" file=\"{0}.stl\"/>\n", mesh);
      body_ << fmt::format("{}<geom type=\"mesh\" mesh=\"{}\" mass=\"0\"/>\n", pad, mesh);
    }
    if (body && body->mass > 0.0) {
      Matrix3 I = body->inertia * body->mass / (units::kKilogram * units::kMetre * units::kMetre);
      // MuJoCo refuses an inertia that is not positive definite (some of GraspIt!'s files give
      // one); such a body gets a solid sphere's of its radius instead.
      const Eigen::SelfAdjointEigenSolver<Matrix3> eigen(I);
      const Vector3 moments = eigen.eigenvalues();
      if (!(moments.minCoeff() > 1e-9 * moments.maxCoeff()) ||
          !(moments.x() + moments.y() >= moments.z())) {
        const double r = std::max(body->maxRadius, 1.0) / units::kMetre;
        I = Matrix3::Identity() * 0.4 * body->mass / units::kKilogram * r * r;
      }
      const Vector3 c = body->cog / units::kMetre;
      body_ << fmt::format(
          "{}<inertial pos=\"{} {} {}\" mass=\"{}\" fullinertia=\"{} {} {} {} {} {}\"/>\n", pad,
          io::exactNumber(c.x()), io::exactNumber(c.y()), io::exactNumber(c.z()),
          io::exactNumber(body->mass / units::kKilogram), io::exactNumber(I(0, 0)),
          io::exactNumber(I(1, 1)), io::exactNumber(I(2, 2)), io::exactNumber(I(0, 1)),
          io::exactNumber(I(0, 2)), io::exactNumber(I(1, 2)));
    } else {
      placeholderInertia(indent);
    }
  }

  void placeholderInertia(int indent) {
    body_ << fmt::format("{}<inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n",
                         std::string(indent, ' '), io::exactNumber(kPlaceholderMass),
                         io::exactNumber(1e-12), io::exactNumber(1e-12), io::exactNumber(1e-12));
  }

  void chain(int c) {
    const KinematicChain& chain = robot_.chains[c];
    // The open bodies' frames at the zero joint vector, palm frame: each new body is placed
    // relative to the innermost open one.
    Transform parent_frame = Transform::Identity();
    Transform before = chain.base;  // the DH frame before the next joint, palm frame
    int open = 0;
    int indent = 6;
    for (std::size_t j = 0; j < chain.joints.size(); ++j) {
      const Joint& joint = chain.joints[j];
      const Transform after = before * joint.transform(0.0);
      const Link* link = nullptr;
      for (const Link& l : chain.links)
        if (l.lastJoint == static_cast<int>(j)) link = &l;
      // The body: the link at its frame, or a placeholder at the DH frame after the joint.
      const Transform frame = link ? after * link->frame : after;
      const std::string body_name = name(link ? link->name : fmt::format("chain{}_joint{}", c, j));
      if (link) link_body_[{c, static_cast<int>(link - chain.links.data())}] = body_name;
      body_ << fmt::format("{}<body name=\"{}\" {}>\n", std::string(indent, ' '), body_name,
                           placement(parent_frame.inverse() * frame));
      // The joint's axis: z of the DH frame before it, seen from the body.
      const Transform axis = frame.inverse() * before;
      const Vector3 p = axis.translation() / units::kMetre;
      const Vector3 z = axis.linear().col(2);
      const std::string joint_name = name(fmt::format("joint{}", chain.firstJoint + j));
      const bool prismatic = joint.type == JointType::Prismatic;
      const double unit = prismatic ? units::kMetre : 1.0;
      body_ << fmt::format(
          "{}  <joint name=\"{}\" type=\"{}\" pos=\"{} {} {}\" axis=\"{} {} {}\" limited=\"true\" "
          "range=\"{} {}\"/>\n",
          std::string(indent, ' '), joint_name, prismatic ? "slide" : "hinge",
          io::exactNumber(p.x()), io::exactNumber(p.y()), io::exactNumber(p.z()),
          io::exactNumber(z.x()), io::exactNumber(z.y()), io::exactNumber(z.z()),
          io::exactNumber(joint.min / unit), io::exactNumber(joint.max / unit));
      couple(joint, joint_name);
      if (link)
        contents(body_name, link->body.get(), indent + 2);
      else
        placeholderInertia(indent + 2);
      parent_frame = frame;
      before = after;
      ++open;
      indent += 2;
    }
    for (; open > 0; --open) {
      indent -= 2;
      body_ << fmt::format("{}</body>\n", std::string(indent, ' '));
    }
  }

  // The pairs graspkit never checks and MuJoCo would (it leaves out only a body and its
  // parent): one chain's links, and the robot's own exclusions with their reasons.
  std::string exclusions() const {
    std::ostringstream out;
    auto body = [&](const LinkRef& ref) {
      return ref.isBase() ? std::string("palm") : link_body_.at({ref.chain, ref.link});
    };
    for (std::size_t c = 0; c < robot_.chains.size(); ++c) {
      const int links = static_cast<int>(robot_.chains[c].links.size());
      for (int a = 0; a < links; ++a)
        for (int b = a + 2; b < links; ++b)  // a body and its parent MuJoCo leaves out itself
          out << fmt::format("    <exclude body1=\"{}\" body2=\"{}\"/>\n",
                             body({static_cast<int>(c), a}), body({static_cast<int>(c), b}));
    }
    for (const CollisionPair& pair : robot_.disabledCollisions)
      out << fmt::format("    <exclude body1=\"{}\" body2=\"{}\"/>\n", body(pair.first),
                         body(pair.second));
    return out.str();
  }

  // One position actuator per DOF, on the DOF's first joint, so that the file reads back (in
  // graspkit, one DOF per actuator) with the robot's DOFs; gains in MuJoCo's units.
  std::string actuators() const {
    std::ostringstream out;
    for (std::size_t d = 0; d < robot_.dofs.size(); ++d) {
      const auto first = first_joint_.find(static_cast<int>(d));
      if (first == first_joint_.end()) continue;
      const bool prismatic = first_prismatic_.at(static_cast<int>(d));
      const double kp = robot_.dofs[d].Kp / (prismatic ? 1e3 : 1e9);  // N/m or N m/rad
      out << fmt::format("    <position name=\"dof{}\" joint=\"{}\" kp=\"{}\"/>\n", d,
                         first->second.first, io::exactNumber(kp > 0.0 ? kp : 1.0));
    }
    const std::string text = out.str();
    return text.empty() ? text : "  <actuator>\n" + text + "  </actuator>\n";
  }

  // A DOF's joints after its first follow it: q_j = (ratio_j / ratio_first) q_first.
  void couple(const Joint& joint, const std::string& joint_name) {
    const auto first = first_joint_.find(joint.dof);
    if (first == first_joint_.end()) {
      first_joint_[joint.dof] = {joint_name, joint.ratio};
      first_prismatic_[joint.dof] = joint.type == JointType::Prismatic;
      return;
    }
    equalities_ << fmt::format("    <joint joint1=\"{}\" joint2=\"{}\" polycoef=\"0 {} 0 0 0\"/>\n",
                               joint_name, first->second.first,
                               io::exactNumber(joint.ratio / first->second.second));
  }

  const RobotModel& robot_;
  fs::path folder_;
  std::set<std::string> used_;
  std::ostringstream assets_, body_, equalities_;
  std::map<int, std::pair<std::string, double>> first_joint_;
  std::map<int, bool> first_prismatic_;
  std::map<std::pair<int, int>, std::string> link_body_;  // (chain, link) -> body name
};

}  // namespace

fs::path saveMjcf(const RobotModel& robot, const fs::path& folder) {
  for (const KinematicChain& chain : robot.chains)
    for (const Joint& joint : chain.joints)
      if (joint.ratio == 0.0)
        throw Error(
            fmt::format("robot '{}': a joint coupled with ratio 0 has no MJCF form", robot.name));
  return MjcfWriter(robot, folder).write();
}

}  // namespace graspkit
