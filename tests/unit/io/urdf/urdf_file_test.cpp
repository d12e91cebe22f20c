// URDF robots against forward kinematics composed here the URDF way (each joint's origin, then
// its rotation or slide about its axis, then the geometry's origin): a two-finger gripper on
// one prismatic DOF with a mimic joint, a three-finger hand with tilted joint origins and
// mimic couplings, a palm that branches through fixed joints, and a mesh found through a
// package path. The engine turns URDF joints into DH chains; the world positions of the links'
// geometry must stay the URDF's at every joint vector. Bad files give errors naming file, line
// and element.

#include "graspkit/io/urdf/urdf_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/material.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

fs::path writeTestFile(const std::string& name, const std::string& text) {
  const fs::path file = test::scratchDir() / name;
  std::ofstream(file) << text;
  return file;
}

Transform origin(const Vector3& xyz_m, const Vector3& rpy = Vector3::Zero()) {
  Transform t = Transform::Identity();
  // URDF rpy: fixed axes x, then y, then z: R = Rz(yaw) Ry(pitch) Rx(roll).
  t.linear() =
      (Eigen::AngleAxisd(rpy.z(), Vector3::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vector3::UnitY()) *
       Eigen::AngleAxisd(rpy.x(), Vector3::UnitX()))
          .toRotationMatrix();
  t.translation() = 1000.0 * xyz_m;
  return t;
}

Transform axisRotation(const Vector3& axis, double angle) {
  Transform t = Transform::Identity();
  t.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return t;
}

Transform slide(const Vector3& axis, double metres) {
  Transform t = Transform::Identity();
  t.translation() = 1000.0 * metres * axis.normalized();
  return t;
}

// The centre of a link's geometry in the world, as the engine places it: the centroid of the
// link mesh's vertices (a box's eight corners) carried by the link pose.
Vector3 meshCentre(const Robot& robot, int chain, int link) {
  const TriangleMesh& mesh = *robot.model().chains[chain].links[link].body->mesh;
  Vector3 sum = Vector3::Zero();
  for (const Vector3& v : mesh.vertices) sum += v;
  return robot.linkPose(chain, link) * (sum / static_cast<double>(mesh.vertices.size()));
}

void expectNear(const Vector3& actual, const Vector3& expected) {
  EXPECT_LT((actual - expected).norm(), 1e-6)
      << actual.transpose() << " vs " << expected.transpose();
}

// A link pose is the URDF link frame: position within 1e-6 mm, axes within 1e-9.
void expectSamePose(const Transform& actual, const Transform& expected) {
  expectNear(actual.translation(), expected.translation());
  EXPECT_LT((actual.linear() - expected.linear()).norm(), 1e-9) << "\n"
                                                                << actual.linear() << "\nvs\n"
                                                                << expected.linear();
}

const char* kGripper = R"(<?xml version="1.0"?>
<robot name="gripper">
  <link name="palm">
    <collision><geometry><box size="0.08 0.04 0.02"/></geometry></collision>
    <inertial><mass value="0.5"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="2e-4" iyz="0" izz="3e-4"/></inertial>
  </link>
  <link name="left">
    <collision><origin xyz="0 0 0.02"/><geometry><box size="0.01 0.02 0.04"/></geometry></collision>
  </link>
  <link name="right">
    <visual><origin xyz="0 0 0.02"/><geometry><box size="0.01 0.02 0.04"/></geometry></visual>
  </link>
  <joint name="left_slide" type="prismatic">
    <parent link="palm"/><child link="left"/>
    <origin xyz="-0.03 0 0.01"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.025" effort="20" velocity="0.1"/>
  </joint>
  <joint name="right_slide" type="prismatic">
    <parent link="palm"/><child link="right"/>
    <origin xyz="0.03 0 0.01" rpy="0 0 3.141592653589793"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.025" effort="20" velocity="0.1"/>
    <mimic joint="left_slide" multiplier="1" offset="0"/>
  </joint>
</robot>
)";

TEST(UrdfFile, GripperSlidesBothFingersOnOneDof) {
  const auto model = loadUrdfFile(writeTestFile("gripper.urdf", kGripper));
  EXPECT_EQ(model->name, "gripper");
  ASSERT_EQ(model->dofs.size(), 1u);
  ASSERT_EQ(model->chains.size(), 2u);
  EXPECT_NEAR(model->dofs[0].min, 0.0, 1e-12);
  EXPECT_NEAR(model->dofs[0].max, 25.0, 1e-9);          // mm
  EXPECT_NEAR(model->dofs[0].maxEffort, 20.0e6, 1e-3);  // 20 N
  EXPECT_EQ(model->palm->mesh->triangleCount(), 12u);
  EXPECT_NEAR(model->palm->mass, 500.0, 1e-9);
  // 1e-4 kg m^2 over 0.5 kg is 200 mm^2 per unit mass.
  EXPECT_NEAR(model->palm->inertia(0, 0), 200.0, 1e-6);
  EXPECT_NEAR(model->palm->inertia(2, 2), 600.0, 1e-6);
  Robot robot(model);
  for (const double q : {0.0, 0.01, 0.025}) {
    SCOPED_TRACE(q);
    robot.setDofValues(std::vector<double>{1000.0 * q});
    expectNear(meshCentre(robot, 0, 0), 1000.0 * Vector3(-0.03 + q, 0, 0.03));
    expectNear(meshCentre(robot, 1, 0), 1000.0 * Vector3(0.03 - q, 0, 0.03));
    expectSamePose(robot.linkPose(0, 0), origin(Vector3(-0.03 + q, 0, 0.01)));
    expectSamePose(robot.linkPose(1, 0), origin(Vector3(0.03 - q, 0, 0.01), Vector3(0, 0, M_PI)));
  }
}

// Full precision, so the file holds the numbers the expectations use.
std::string num(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

TEST(UrdfFile, LinksAreRubberUnlessTheOptionsSayOtherwise) {
  const fs::path file = writeTestFile("gripper.urdf", kGripper);
  const auto plain = loadUrdfFile(file);
  EXPECT_EQ(plain->palm->material, Material::Rubber);
  EXPECT_EQ(plain->chains[0].links[0].body->material, Material::Rubber);
  LoadOptions options;
  options.urdfMaterial = Material::Plastic;
  options.urdfLinkMaterials = {{"left", Material::Metal}};
  const auto chosen = loadUrdfFile(file, options);
  EXPECT_EQ(chosen->palm->material, Material::Plastic);
  options.urdfLinkMaterials = {{"palm", Material::Wood}};
  EXPECT_EQ(loadUrdfFile(file, options)->palm->material, Material::Wood);
  options.urdfLinkMaterials = {{"left", Material::Metal}};
  EXPECT_EQ(chosen->chains[0].links[0].body->material, Material::Metal);
  EXPECT_EQ(chosen->chains[1].links[0].body->material, Material::Plastic);
  options.urdfLinkMaterials = {{"thumb", Material::Metal}};
  EXPECT_THROW(loadUrdfFile(file, options), Error);
}

// Three fingers round a palm, each turned about z by its mount's yaw and tilted; a proximal
// joint about the mount's y axis, a distal one mimicking it (multiplier 0.5, offset 0.2 rad)
// about an axis off the principal ones.
std::string threeFingerHand() {
  std::string text = R"(<?xml version="1.0"?>
<robot name="three_finger">
  <link name="palm"><collision><geometry><cylinder radius="0.04" length="0.02"/></geometry></collision></link>
)";
  for (int f = 0; f < 3; ++f) {
    const std::string n = std::to_string(f);
    const double yaw = 2.0 * M_PI * f / 3.0;
    text += "  <link name=\"prox" + n +
            "\"><collision><origin xyz=\"0 0 0.025\"/><geometry><box size=\"0.015 0.015 "
            "0.05\"/></geometry></collision></link>\n";
    text += "  <link name=\"dist" + n +
            "\"><collision><origin xyz=\"0 0 0.015\" rpy=\"0.1 0 0\"/><geometry><box "
            "size=\"0.012 0.012 0.03\"/></geometry></collision></link>\n";
    text += "  <joint name=\"j" + n +
            "a\" type=\"revolute\"><parent link=\"palm\"/><child link=\"prox" + n +
            "\"/><origin xyz=\"" + num(0.035 * std::cos(yaw)) + " " + num(0.035 * std::sin(yaw)) +
            " 0.01\" rpy=\"0.05 -0.1 " + num(yaw) +
            "\"/><axis xyz=\"0 1 0\"/><limit lower=\"-0.5\" upper=\"1.5\" effort=\"2\" "
            "velocity=\"1\"/></joint>\n";
    text += "  <joint name=\"j" + n + "b\" type=\"revolute\"><parent link=\"prox" + n +
            "\"/><child link=\"dist" + n +
            "\"/><origin xyz=\"0.002 0 0.05\" rpy=\"0 0.2 0\"/><axis xyz=\"0.1 1 0.2\"/><limit "
            "lower=\"-1\" upper=\"2\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j" +
            n + "a\" multiplier=\"0.5\" offset=\"0.2\"/></joint>\n";
  }
  return text + "</robot>\n";
}

TEST(UrdfFile, ThreeFingerHandFollowsTheUrdfKinematicsWithMimicJoints) {
  const auto model = loadUrdfFile(writeTestFile("three_finger.urdf", threeFingerHand()));
  ASSERT_EQ(model->dofs.size(), 3u);
  ASSERT_EQ(model->chains.size(), 3u);
  Robot robot(model);
  for (const double q : {-0.4, 0.0, 0.7, 1.4}) {
    SCOPED_TRACE(q);
    robot.setDofValues(std::vector<double>{q, 0.5 * q, -0.3 * q});
    for (int f = 0; f < 3; ++f) {
      SCOPED_TRACE(f);
      const double dof = robot.dofValues()[f];
      const double yaw = 2.0 * M_PI * f / 3.0;
      const Transform proximal = origin(Vector3(0.035 * std::cos(yaw), 0.035 * std::sin(yaw), 0.01),
                                        Vector3(0.05, -0.1, yaw)) *
                                 axisRotation(Vector3::UnitY(), dof);
      const Transform distal = proximal * origin(Vector3(0.002, 0, 0.05), Vector3(0, 0.2, 0)) *
                               axisRotation(Vector3(0.1, 1, 0.2), 0.5 * dof + 0.2);
      expectNear(meshCentre(robot, f, 0), proximal * Vector3(0, 0, 25));
      expectNear(meshCentre(robot, f, 1), distal * Vector3(0, 0, 15));
      expectSamePose(robot.linkPose(f, 0), proximal);
      expectSamePose(robot.linkPose(f, 1), distal);
    }
  }
}

// A URDF hand written as GraspIt! XML (its link frames baked into the meshes, GraspIt!'s links
// sitting at their DH frames) puts every vertex of every link where the URDF does.
TEST(UrdfFile, WrittenAsGraspitXmlTheGeometryStaysPut) {
  const auto urdf = loadUrdfFile(writeTestFile("hand.urdf", threeFingerHand()));
  const auto graspit = loadRobotFile(saveRobotFile(*urdf, test::scratchDir()));
  ASSERT_EQ(graspit->chains.size(), urdf->chains.size());
  Robot a(urdf), b(graspit);
  for (const double q : {-0.3, 1.1}) {
    const std::vector<double> values{q, 0.5 * q, 0.2};
    a.setDofValues(values);
    b.setDofValues(values);
    for (int c = 0; c < 3; ++c) {
      for (int l = 0; l < 2; ++l) {
        const TriangleMesh& ma = *urdf->chains[c].links[l].body->mesh;
        const TriangleMesh& mb = *graspit->chains[c].links[l].body->mesh;
        ASSERT_EQ(ma.vertices.size(), mb.vertices.size());
        for (std::size_t v = 0; v < ma.vertices.size(); ++v)
          expectNear(b.linkPose(c, l) * mb.vertices[v], a.linkPose(c, l) * ma.vertices[v]);
      }
    }
  }
}

// The palm is a plate on the root link through a fixed joint, which carries two finger mounts,
// also fixed: all one body. Each mount's finger is a chain.
const char* kBranchingPalm = R"(<?xml version="1.0"?>
<robot name="tree">
  <link name="base"><collision><geometry><box size="0.05 0.05 0.01"/></geometry></collision></link>
  <link name="plate"><collision><geometry><box size="0.06 0.02 0.005"/></geometry></collision></link>
  <link name="mount_a"><collision><geometry><sphere radius="0.005"/></geometry></collision></link>
  <link name="mount_b"/>
  <link name="finger_a"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <link name="finger_b"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <joint name="plate_fix" type="fixed"><parent link="base"/><child link="plate"/><origin xyz="0 0 0.01"/></joint>
  <joint name="a_fix" type="fixed"><parent link="plate"/><child link="mount_a"/><origin xyz="0.025 0 0" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="b_fix" type="fixed"><parent link="plate"/><child link="mount_b"/><origin xyz="-0.025 0 0"/></joint>
  <joint name="a" type="continuous"><parent link="mount_a"/><child link="finger_a"/><axis xyz="1 0 0"/></joint>
  <joint name="b" type="revolute"><parent link="mount_b"/><child link="finger_b"/><axis xyz="0 -1 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";

TEST(UrdfFile, FixedJointsJoinTheirLinksAndEachBranchIsAChain) {
  const auto model = loadUrdfFile(writeTestFile("tree.urdf", kBranchingPalm));
  ASSERT_EQ(model->chains.size(), 2u);
  ASSERT_EQ(model->dofs.size(), 2u);
  // base (12) + plate (12) + mount_a's sphere (16 bands x 32: 2 x 32 caps + 14 x 64 quads).
  EXPECT_EQ(model->palm->mesh->triangleCount(), 12u + 12u + (2u * 32u + 14u * 64u));
  EXPECT_NEAR(model->dofs[0].min, -M_PI, 1e-12);  // continuous
  Robot robot(model);
  for (const double q : {0.0, 0.6}) {
    SCOPED_TRACE(q);
    robot.setDofValues(std::vector<double>{q, q});
    const Transform a = origin(Vector3(0, 0, 0.01)) *
                        origin(Vector3(0.025, 0, 0), Vector3(0, 0, M_PI / 2)) *
                        axisRotation(Vector3::UnitX(), q);
    const Transform b = origin(Vector3(0, 0, 0.01)) * origin(Vector3(-0.025, 0, 0)) *
                        axisRotation(-Vector3::UnitY(), q);
    expectNear(meshCentre(robot, 0, 0), a * Vector3(0, 0, 20));
    expectNear(meshCentre(robot, 1, 0), b * Vector3(0, 0, 20));
    expectSamePose(robot.linkPose(0, 0), a);
    expectSamePose(robot.linkPose(1, 0), b);
  }
}

TEST(UrdfFile, LoadsThroughRobotFilesAndFindsPackageMeshes) {
  // An ASCII STL tetrahedron in metres, in a package folder the URDF names by package://.
  const fs::path packages = test::scratchDir() / "packages";
  const fs::path package = packages / "my_hand";
  fs::create_directories(package / "meshes");
  std::ofstream(package / "meshes" / "tip.stl") << R"(solid tip
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 0.01 0
  vertex 0.01 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0.01 0 0
  vertex 0 0 0.01
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0.01
  vertex 0 0.01 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 0.01 0 0
  vertex 0 0.01 0
  vertex 0 0 0.01
 endloop
endfacet
endsolid tip
)";
  const fs::path file = writeTestFile("packaged.urdf", R"(<?xml version="1.0"?>
<robot name="packaged">
  <link name="palm"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
  <link name="tip"><collision><geometry><mesh filename="package://my_hand/meshes/tip.stl" scale="2 2 2"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="palm"/><child link="tip"/><origin xyz="0 0 0.02"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>
)");
  LoadOptions options;
  options.packagePaths = {packages};
  const auto model = loadRobotFile(file, options);
  ASSERT_EQ(model->chains.size(), 1u);
  const TriangleMesh& tip = *model->chains[0].links[0].body->mesh;
  EXPECT_EQ(tip.triangleCount(), 4u);
  Robot robot(model);
  robot.setDofValues(std::vector<double>{0.0});
  // The tetrahedron's corners at 2 x 10 mm, above the joint at z = 20 mm (STL stores floats).
  double top = -1e9;
  for (const Vector3& v : tip.vertices) top = std::max(top, (robot.linkPose(0, 0) * v).z());
  EXPECT_NEAR(top, 40.0, 1e-5);
  // Without the package path the mesh is not found, and the error says where it was asked for.
  try {
    loadUrdfFile(file);
    FAIL() << "a package mesh was found without its package path";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("my_hand"), std::string::npos) << e.what();
    EXPECT_EQ(e.where().line, 4) << e.what();
  }
}

struct BadUrdf {
  const char* name;
  const char* body;      // inside <robot>
  int line;              // of the element the error names (the XML declaration is line 1)
  const char* expected;  // in the message
};

TEST(UrdfFile, BadFilesNameFileLineAndElement) {
  const std::string links = "<link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>\n";  // line 3
  const BadUrdf cases[] = {
      {"cycle",
       "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
       "<joint name=\"bc\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>\n"
       "<joint name=\"ca\" type=\"fixed\"><parent link=\"c\"/><child link=\"a\"/></joint>\n",
       0, "cycle"},
      {"two_parents",
       "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
       "<joint name=\"cb\" type=\"fixed\"><parent link=\"c\"/><child link=\"b\"/></joint>\n",
       5, "child of joints"},
      {"missing_mesh",
       "<link name=\"d\"><visual><geometry><mesh filename=\"nowhere.stl\"/></geometry></visual>"
       "</link>\n"
       "<joint name=\"ad\" type=\"fixed\"><parent link=\"a\"/><child link=\"d\"/></joint>\n"
       "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
       "<joint name=\"ac\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>\n",
       4, "nowhere.stl"},
      {"zero_axis",
       "<joint name=\"ab\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n"
       "<axis xyz=\"0 0 0\"/><limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"
       "</joint>\n",
       5, "axis is zero"},
      {"mimic_missing",
       "<joint name=\"ab\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n"
       "<axis xyz=\"0 0 1\"/><limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"
       "<mimic joint=\"ghost\"/></joint>\n",
       5, "ghost"},
      {"no_axis",
       "<joint name=\"ab\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>\n"
       "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n",
       4, "needs <axis"},
      {"nan_limit",
       "<joint name=\"ab\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n"
       "<limit lower=\"nan\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n",
       5, "finite"},
      {"floating",
       "<joint name=\"ab\" type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint>\n", 4,
       "not supported"},
  };
  for (const BadUrdf& bad : cases) {
    SCOPED_TRACE(bad.name);
    const fs::path file =
        writeTestFile(std::string(bad.name) + ".urdf",
                      std::string("<?xml version=\"1.0\"?>\n<robot name=\"bad\">\n") + links +
                          bad.body + "</robot>\n");
    try {
      loadUrdfFile(file);
      ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad.expected), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, file.string()) << e.what();
      if (bad.line > 0) EXPECT_EQ(e.where().line, bad.line) << e.what();
      EXPECT_FALSE(e.where().element.empty()) << e.what();
    }
  }
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// A gripper whose second finger mimics the first with multiplier -1 and carries the same limits
// [0, 0.548] as the first: intersected, they would leave the DOF [0, 0]. ROS ignores a mimic
// joint's limits; so does graspkit, with a warning that names the mimic.
TEST(UrdfFile, AMimicJointsOwnLimitsNeverCollapseItsDof) {
  const std::string text = R"(<?xml version="1.0"?>
<robot name="mirror">
  <link name="palm"><collision><geometry><box size="0.08 0.04 0.02"/></geometry></collision></link>
  <link name="a"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <link name="b"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <joint name="ja" type="revolute">
    <parent link="palm"/><child link="a"/><origin xyz="-0.03 0 0"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.548" effort="1" velocity="1"/>
  </joint>
  <joint name="jb" type="revolute">
    <parent link="palm"/><child link="b"/><origin xyz="0.03 0 0"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.548" effort="1" velocity="1"/>
    <mimic joint="ja" multiplier="-1" offset="0"/>
  </joint>
</robot>
)";
  std::vector<Warning> warnings;
  const WarningHandler previous =
      setWarningHandler([&](const Warning& w) { warnings.push_back(w); });
  const auto model = loadUrdfFile(writeTestFile("mirror.urdf", text));
  setWarningHandler(previous);
  ASSERT_EQ(model->dofs.size(), 1u);
  EXPECT_DOUBLE_EQ(model->dofs[0].min, 0.0);
  EXPECT_DOUBLE_EQ(model->dofs[0].max, 0.548);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].message.find("'jb'"), std::string::npos) << warnings[0].message;
  EXPECT_EQ(warnings[0].where.line, 10);
  // At the DOF's top the mimic stands at -0.548, mirrored.
  Robot robot(model);
  robot.setDofValues(std::vector<double>{0.548});
  expectSamePose(robot.linkPose(1, 0),
                 origin({0.03, 0, 0}) * axisRotation(Vector3::UnitY(), -0.548));
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// A palm arch (a joint about z) carrying two fingers, as some hands' ring and little fingers
// hang: a tree below a moving joint. Each path from the palm is a chain; the arch's joint is in
// both, driven by its one DOF, and the arch link belongs to the first. Every link stays where
// URDF's composition puts it.
TEST(UrdfFile, AJointCarryingTwoFingersMovesBoth) {
  const std::string text = R"(<?xml version="1.0"?>
<robot name="arch">
  <link name="palm"><collision><geometry><box size="0.08 0.04 0.02"/></geometry></collision></link>
  <link name="index"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <link name="arch"><collision><geometry><box size="0.03 0.01 0.01"/></geometry></collision></link>
  <link name="ring"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <link name="little"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <joint name="index" type="revolute"><parent link="palm"/><child link="index"/>
    <origin xyz="0.03 0 0.05"/><axis xyz="0 1 0"/><limit lower="0" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="arch" type="revolute"><parent link="palm"/><child link="arch"/>
    <origin xyz="-0.02 0 0.02"/><axis xyz="0 0 1"/><limit lower="-0.5" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="ring" type="revolute"><parent link="arch"/><child link="ring"/>
    <origin xyz="0.01 0 0.03"/><axis xyz="0 1 0"/><limit lower="0" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="little" type="revolute"><parent link="arch"/><child link="little"/>
    <origin xyz="-0.01 0 0.03"/><axis xyz="0 1 0"/><limit lower="0" upper="1.5" effort="1" velocity="1"/></joint>
</robot>
)";
  const auto model = loadUrdfFile(writeTestFile("arch.urdf", text));
  ASSERT_EQ(model->dofs.size(), 4u);  // index, arch, ring, little
  ASSERT_EQ(model->chains.size(), 3u);
  std::map<std::string, LinkRef> links;
  for (std::size_t c = 0; c < model->chains.size(); ++c)
    for (std::size_t l = 0; l < model->chains[c].links.size(); ++l)
      links[model->chains[c].links[l].name] = {static_cast<int>(c), static_cast<int>(l)};
  ASSERT_EQ(links.size(), 4u);                  // each link once: index, arch, ring, little
  EXPECT_EQ(model->dofs[1].joints.size(), 2u);  // the arch joint, in two chains
  Robot robot(model);
  for (const auto& q :
       {std::vector<double>{0.3, 0.4, 0.2, 1.1}, std::vector<double>{1.0, -0.45, 1.3, 0.1}}) {
    robot.setDofValues(q);
    const Transform arch = origin({-0.02, 0, 0.02}) * axisRotation(Vector3::UnitZ(), q[1]);
    expectSamePose(robot.linkPose(links.at("index")),
                   origin({0.03, 0, 0.05}) * axisRotation(Vector3::UnitY(), q[0]));
    expectSamePose(robot.linkPose(links.at("arch")), arch);
    expectSamePose(robot.linkPose(links.at("ring")),
                   arch * origin({0.01, 0, 0.03}) * axisRotation(Vector3::UnitY(), q[2]));
    expectSamePose(robot.linkPose(links.at("little")),
                   arch * origin({-0.01, 0, 0.03}) * axisRotation(Vector3::UnitY(), q[3]));
  }
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// A URDF is bounded as GraspIt!'s robot files are (1024 DOFs, 4096 joints and links), and the
// bound is met before anything quadratic runs: a 5,000-link chain is refused at its 4,097th link.
std::string longChain(int links, bool movable) {
  std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"long\">\n";
  for (int i = 0; i < links; ++i) text += fmt::format("<link name=\"l{}\"/>\n", i);
  for (int i = 1; i < links; ++i) {
    text += fmt::format(
        "<joint name=\"j{}\" type=\"{}\"><parent link=\"l{}\"/><child link=\"l{}\"/>"
        "<origin xyz=\"0 0 0.001\"/><axis xyz=\"0 1 0\"/>"
        "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n",
        i, movable ? "revolute" : "fixed", i - 1, i);
  }
  return text + "</robot>\n";
}

TEST(UrdfFile, RobotsPastTheLimitsAreRefusedNamingTheElement) {
  try {
    loadUrdfFile(writeTestFile("too_many_links.urdf", longChain(5000, false)));
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 4096 links"), std::string::npos) << e.what();
    EXPECT_GT(e.where().line, 4000);
  }
  try {
    loadUrdfFile(writeTestFile("too_many_dofs.urdf", longChain(1100, true)));
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1024 DOFs"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// Numbers urdfdom would take quietly (dropping a NaN mass, keeping an axis it cannot normalise)
// are refused by graspkit with the element: NaN and infinite values, a negative mass, sizes that
// are not positive, and values past a million (an axis 1e308 1e308 0 has no direction).
TEST(UrdfFile, NumbersUrdfdomWouldTakeAreCheckedFirst) {
  const std::string link_part =
      R"(<link name="palm"><collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision></link>)";
  const std::string joint =
      R"(<joint name="j" type="revolute"><parent link="palm"/><child link="f"/>
    <origin xyz="%ORIGIN%"/><axis xyz="%AXIS%"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>)";
  struct Case {
    const char* name;
    std::string finger;
    std::string origin = "0 0 0.01";
    std::string axis = "0 1 0";
    const char* message;
  };
  const std::string box =
      R"(<collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision>)";
  const Case cases[] = {
      {"nan_mass",
       R"(<inertial><mass value="nan"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>)" +
           box,
       "0 0 0.01", "0 1 0", "not a finite number"},
      {"negative_mass",
       R"(<inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>)" +
           box,
       "0 0 0.01", "0 1 0", "negative mass"},
      {"zero_box", R"(<collision><geometry><box size="0 0.01 0.04"/></geometry></collision>)",
       "0 0 0.01", "0 1 0", "must be positive"},
      {"inf_radius", R"(<collision><geometry><sphere radius="inf"/></geometry></collision>)",
       "0 0 0.01", "0 1 0", "not a finite number"},
      {"huge_axis", box, "0 0 0.01", "1e308 1e308 0", "within +-1e6"},
      {"huge_origin", box, "1e308 0 0", "0 1 0", "within +-1e6"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::string j = joint;
    j.replace(j.find("%ORIGIN%"), 8, c.origin);
    j.replace(j.find("%AXIS%"), 6, c.axis);
    const std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n" + link_part +
                             "\n<link name=\"f\">" + c.finger + "</link>\n" + j + "\n</robot>\n";
    try {
      loadUrdfFile(writeTestFile(std::string(c.name) + ".urdf", text));
      ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      EXPECT_GT(e.where().line, 0) << e.what();
    }
  }
}

}  // namespace
}  // namespace graspkit
