#include "graspkit/io/graspit/robot_export.hpp"

// Writing a robot as GraspIt! XML: the robot file, and per body a Body XML with its OFF mesh in
// the robot's iv/ folder (where GraspIt! looks). GraspIt!'s links sit at their DH frames, so a
// link with its own frame (a URDF link) has that frame baked into its mesh and mass properties.

#include <fmt/format.h>

#include <algorithm>

#include <set>
#include <sstream>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "io/common/export_text.hpp"
#include "io/common/off_text.hpp"

namespace graspkit {

namespace fs = std::filesystem;

namespace {

std::string number(double value) {
  return fmt::format("{}", value);
}  // shortest exact

// A coupling ratio without an exponent: the d#*k+c reader takes digits, '.' and '-'.
std::string ratio(double value) {
  std::string text = fmt::format("{:.17f}", value);
  while (text.size() > 1 && text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

class GraspitWriter {
 public:
  GraspitWriter(const RobotModel& robot, const fs::path& folder) : robot_(robot), folder_(folder) {}

  fs::path write() {
    createOutputFolder(folder_ / "iv");
    std::ostringstream xml;
    xml << "<?xml version=\"1.0\" ?>\n";
    xml << fmt::format("<!-- written by graspkit from {} -->\n",
                       io::xmlCommentText(robot_.file.filename().string()));
    xml << fmt::format("<robot type=\"{}\">\n", io::xmlEscaped(robot_.type));
    xml << fmt::format("    <palm>{}</palm>\n",
                       body("palm", robot_.palm.get(), Transform::Identity()));
    for (const Dof& dof : robot_.dofs) {
      xml << fmt::format(
          "    <dof type=\"{}\">\n        <defaultVelocity>{}</defaultVelocity>\n"
          "        <maxEffort>{}</maxEffort>\n        <Kp>{}</Kp>\n        <Kd>{}</Kd>\n"
          "        <draggerScale>20</draggerScale>\n",
          dofTypeLetter(dof.type), number(dof.defaultVelocity), number(dof.maxEffort),
          number(dof.Kp), number(dof.Kd));
      if (dof.type == DofType::Breakaway)
        xml << fmt::format("        <breakAwayTorque>{}</breakAwayTorque>\n",
                           number(dof.breakAwayTorque / 1000.0));
      xml << "    </dof>\n";
    }
    for (std::size_t c = 0; c < robot_.chains.size(); ++c) chain(static_cast<int>(c), xml);
    setup(xml);
    xml << "</robot>\n";
    const fs::path file = folder_ / (io::fileStem(robot_.name, "robot") + ".xml");
    writeFileAtomically(file, xml.str());
    return file;
  }

 private:
  // Writes iv/<name>.xml and iv/<name>.off for `body` moved by `bake`; returns the XML's name.
  std::string body(const std::string& wanted, const BodyModel* body, const Transform& bake) {
    std::string name = wanted;
    for (char& ch : name)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') ch = '_';
    for (int k = 2; !used_.insert(name).second; ++k) name = fmt::format("{}_{}", wanted, k);
    TriangleMesh mesh = body && body->mesh ? *body->mesh : TriangleMesh{};
    transformMesh(mesh, Eigen::Affine3d(bake.matrix()));
    mesh.triangleColours.clear();
    writeFileAtomically(folder_ / "iv" / (name + ".off"), io::offText(mesh));
    std::string xml = "<?xml version=\"1.0\" ?>\n<root>\n";
    if (body) {
      const Vector3 cog = bake * body->cog;
      const Matrix3 inertia = bake.linear() * body->inertia * bake.linear().transpose();
      xml += fmt::format("    <material>{}</material>\n", nameOf(body->material));
      xml += fmt::format("    <mass>{}</mass>\n", number(body->mass));
      xml += fmt::format("    <cog>{} {} {}</cog>\n", number(cog.x()), number(cog.y()),
                         number(cog.z()));
      xml += fmt::format("    <inertia_matrix>{} {} {} {} {} {} {} {} {}</inertia_matrix>\n",
                         number(inertia(0, 0)), number(inertia(0, 1)), number(inertia(0, 2)),
                         number(inertia(1, 0)), number(inertia(1, 1)), number(inertia(1, 2)),
                         number(inertia(2, 0)), number(inertia(2, 1)), number(inertia(2, 2)));
    }
    xml += fmt::format("    <geometryFile type=\"off\">{}.off</geometryFile>\n</root>\n", name);
    writeFileAtomically(folder_ / "iv" / (name + ".xml"), xml);
    return name + ".xml";
  }

  void chain(int c, std::ostringstream& xml) {
    const KinematicChain& chain = robot_.chains[c];
    const Quaternion q(chain.base.linear());
    const Vector3& p = chain.base.translation();
    xml << fmt::format(
        "    <chain>\n        <transform>\n            <fullTransform>({} {} {} {})[{} {} "
        "{}]</fullTransform>\n        </transform>\n",
        number(q.w()), number(q.x()), number(q.y()), number(q.z()), number(p.x()), number(p.y()),
        number(p.z()));
    for (const Joint& joint : chain.joints) {
      const bool revolute = joint.type == JointType::Revolute;
      const double offset = revolute ? radiansToDegrees(joint.theta) : joint.d;
      const std::string driven =
          fmt::format("d{}*{}+{}", joint.dof, ratio(joint.ratio), number(offset));
      const double scale = revolute ? radiansToDegrees(1.0) : 1.0;
      xml << fmt::format("        <joint type=\"{}\">\n", revolute ? "Revolute" : "Prismatic");
      xml << fmt::format("            <theta>{}</theta>\n",
                         revolute ? driven : number(radiansToDegrees(joint.theta)));
      xml << fmt::format("            <d>{}</d>\n", revolute ? number(joint.d) : driven);
      xml << fmt::format("            <a>{}</a>\n            <alpha>{}</alpha>\n", number(joint.a),
                         number(radiansToDegrees(joint.alpha)));
      xml << fmt::format(
          "            <minValue>{}</minValue>\n            <maxValue>{}</maxValue>\n",
          number(joint.min * scale), number(joint.max * scale));
      xml << "        </joint>\n";
    }
    int consumed_from = 0;
    for (const Link& link : chain.links) {
      const int consumed = link.lastJoint + 1 - consumed_from;
      consumed_from = link.lastJoint + 1;
      const char* type = consumed == 0                                               ? "Fixed"
                         : consumed == 2                                             ? "Universal"
                         : consumed == 3                                             ? "Ball"
                         : chain.joints[link.lastJoint].type == JointType::Prismatic ? "Prismatic"
                                                                                     : "Revolute";
      xml << fmt::format("        <link dynamicJointType=\"{}\">{}</link>\n", type,
                         body(link.name, link.body.get(), link.frame));
    }
    xml << "    </chain>\n";
  }

  // The hand setup a URDF or MJCF hand was given (docs/hands.md), in GraspIt!'s own tags: the
  // switched-off pairs, the approach direction, and the virtual contacts (a file of their own,
  // moved into the DH frames the links are baked into). Closing directions travel as the sign
  // of each DOF's defaultVelocity.
  void setup(std::ostringstream& xml) {
    for (const CollisionPair& p : robot_.disabledCollisions) {
      xml << fmt::format(
          "    <disableCollision body1_chain=\"{}\" body1_link=\"{}\" body2_chain=\"{}\" "
          "body2_link=\"{}\"/>\n",
          p.first.chain, std::max(p.first.link, 0), p.second.chain, std::max(p.second.link, 0));
    }
    if (robot_.approach) {
      const Vector3& r = robot_.approach->referenceLocation;
      const Vector3& d = robot_.approach->direction;
      xml << fmt::format(
          "    <approachDirection>\n        <referenceLocation>{} {} {}</referenceLocation>\n"
          "        <direction>{} {} {}</direction>\n    </approachDirection>\n",
          number(r.x()), number(r.y()), number(r.z()), number(d.x()), number(d.y()), number(d.z()));
    }
    if (robot_.virtualContacts.empty()) return;
    const std::string file = fmt::format("virtual/{}.xml", io::fileStem(robot_.name, "robot"));
    createOutputFolder(folder_ / "virtual");
    std::string text = fmt::format(
        "<?xml version=\"1.0\" ?>\n<virtual_contacts>\n  <robot_name>{}</robot_name>\n"
        "  <num_contacts>{}</num_contacts>\n",
        io::xmlEscaped(robot_.name), robot_.virtualContacts.size());
    auto joined = [](const auto& v) {
      std::string out;
      for (long k = 0; k < v.size(); ++k) {
        if (k > 0) out += ' ';
        out += number(v[k]);
      }
      return out;
    };
    for (const VirtualContact& v : robot_.virtualContacts) {
      const Transform bake =
          v.finger < 0 ? Transform::Identity() : robot_.chains[v.finger].links[v.link].frame;
      const Quaternion rotation(bake.linear() * v.rotation.toRotationMatrix());
      text += fmt::format(
          "  <virtual_contact>\n    <finger_number>{}</finger_number>\n"
          "    <link_number>{}</link_number>\n    <num_friction_edges>{}</num_friction_edges>\n"
          "    <friction_edges>\n",
          v.finger, v.link, v.frictionEdges.size());
      for (const auto& edge : v.frictionEdges)
        text += fmt::format("      <friction_edge>{}</friction_edge>\n", joined(edge));
      text += fmt::format(
          "    </friction_edges>\n    <location>{}</location>\n    <rotation>{} {} {} "
          "{}</rotation>\n    <translation>{}</translation>\n    <normal>{}</normal>\n"
          "    <sCof>{}</sCof>\n  </virtual_contact>\n",
          joined(Vector3(bake * v.location)), number(rotation.w()), number(rotation.x()),
          number(rotation.y()), number(rotation.z()), joined(Vector3(bake * v.translation)),
          joined(Vector3(bake.linear() * v.normal)), number(v.sCof));
    }
    writeFileAtomically(folder_ / file, text + "</virtual_contacts>\n");
    xml << fmt::format("    <virtualContacts>{}</virtualContacts>\n", file);
  }

  const RobotModel& robot_;
  fs::path folder_;
  std::set<std::string> used_;
};

}  // namespace

fs::path saveRobotFile(const RobotModel& robot, const fs::path& folder) {
  return GraspitWriter(robot, folder).write();
}

}  // namespace graspkit
