// MJCF hands against forward kinematics composed here the MuJoCo way (each body's pos and
// orientation in its parent, then its joints' motions about their axes): default classes with
// childclass and class, degrees and an Euler sequence, a fixed tendon whose actuator is one DOF,
// a joint equality with polycoef, and a four-bar parallelogram whose loop the reader closes (its
// followers have a closed form). Bad files give errors naming file, line and element.

#include "graspkit/io/mjcf/mjcf_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// Files of one test share a folder (includes name each other).
fs::path writeFile(const std::string& name, const std::string& text) {
  static const fs::path folder = test::scratchDir();
  const fs::path file = folder / name;
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

Transform translation(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(x, y, z);
  return t;
}

Transform rotation(const Vector3& axis, double angle) {
  Transform t = Transform::Identity();
  t.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return t;
}

void expectPose(const Transform& actual, const Transform& expected, double tolerance = 1e-9) {
  EXPECT_LT((actual.translation() - expected.translation()).norm(), tolerance)
      << actual.translation().transpose() << " vs " << expected.translation().transpose();
  EXPECT_LT((actual.linear() - expected.linear()).norm(), tolerance) << "\n"
                                                                     << actual.linear() << "\nvs\n"
                                                                     << expected.linear();
}

// Two fingers on one tendon (left turns +q, right -q); the left tip follows by an equality.
const char* kTendonHand = R"(<mujoco model="tendon_hand">
  <compiler angle="degree" eulerseq="zyx"/>
  <default>
    <joint axis="0 1 0" range="-90 90"/>
    <geom type="box" size="0.01 0.01 0.02"/>
    <default class="finger">
      <joint damping="0.1"/>
      <default class="tip"><geom type="capsule" size="0.005 0.01"/></default>
    </default>
  </default>
  <worldbody>
    <body name="palm">
      <geom type="box" size="0.04 0.04 0.01"/>
      <body name="left" pos="-0.03 0 0.01" childclass="finger">
        <joint name="left_base"/>
        <geom pos="0 0 0.02"/>
        <body name="left_tip" pos="0 0 0.04" euler="0 0 30">
          <joint name="left_tip_joint"/>
          <geom class="tip" pos="0 0 0.01"/>
          <geom type="sphere" size="0.05" contype="0" conaffinity="0"/>
        </body>
      </body>
      <body name="right" pos="0.03 0 0.01" quat="0 0 0 1">
        <joint name="right_base"/>
        <geom pos="0 0 0.02"/>
      </body>
    </body>
  </worldbody>
  <tendon>
    <fixed name="pair"><joint joint="left_base" coef="2"/><joint joint="right_base" coef="-2"/></fixed>
  </tendon>
  <equality><joint joint1="left_tip_joint" joint2="left_base" polycoef="0.1 0.5 0 0 0"/></equality>
  <actuator><position name="close" tendon="pair" kp="10"/></actuator>
</mujoco>
)";

TEST(MjcfFile, TendonAndEqualityCoupleOneDofAsMujocoMovesTheBodies) {
  const auto model = loadRobotFile(writeFile("tendon_hand.xml", kTendonHand));
  EXPECT_EQ(model->name, "tendon_hand");
  ASSERT_EQ(model->dofs.size(), 1u);
  EXPECT_NEAR(model->dofs[0].min, -M_PI / 2, 1e-12);
  EXPECT_NEAR(model->dofs[0].max, M_PI / 2, 1e-12);
  ASSERT_EQ(model->chains.size(), 2u);
  Robot robot(model);
  for (const double d : {-1.2, -0.3, 0.0, 0.7, 1.5}) {
    SCOPED_TRACE(d);
    robot.setDofValues(std::vector<double>{d});
    const Transform left = translation(-30, 0, 10) * rotation(Vector3::UnitY(), d);
    // euler "0 0 30" with eulerseq zyx: 0 about z, 0 about y, then 30 degrees about x.
    const Transform tip = left * translation(0, 0, 40) * rotation(Vector3::UnitX(), M_PI / 6) *
                          rotation(Vector3::UnitY(), 0.1 + 0.5 * d);
    const Transform right =
        translation(30, 0, 10) * rotation(Vector3::UnitZ(), M_PI) * rotation(Vector3::UnitY(), -d);
    expectPose(robot.linkPose(0, 0), left);
    expectPose(robot.linkPose(0, 1), tip);
    expectPose(robot.linkPose(1, 0), right);
  }
  // The tip's capsule (class "tip" under childclass "finger"), not the visual-only sphere:
  // a 5 mm radius, 10 mm half-length capsule 10 mm up the tip body's z.
  const TriangleMesh& tip = *model->chains[0].links[1].body->mesh;
  Vector3 lo = Vector3::Constant(1e9), hi = Vector3::Constant(-1e9);
  for (const Vector3& v : tip.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_NEAR(lo.z(), -5.0, 1e-9);
  EXPECT_NEAR(hi.z(), 25.0, 1e-9);
  EXPECT_NEAR(hi.x(), 5.0, 1e-9);
}

// A parallelogram four-bar: a crank on the palm at x = 0, a rocker at x = 20 mm, both 40 mm
// long, and a coupler hung on the crank whose far end the connect pins to the rocker's tip.
// Closed form: the rocker turns with the crank, and the coupler keeps its orientation.
const char* kFourBar = R"(<mujoco model="four_bar">
  <compiler angle="radian"/>
  <worldbody>
    <body name="palm">
      <geom type="box" size="0.05 0.05 0.005" pos="0 0 -0.01"/>
      <body name="crank">
        <joint name="crank" axis="0 1 0" range="-0.8 0.8"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.04" size="0.002"/>
        <body name="coupler" pos="0 0 0.04">
          <joint name="coupler" axis="0 1 0" range="-1 1"/>
          <geom type="capsule" fromto="0 0 0 0.02 0 0" size="0.002"/>
        </body>
      </body>
      <body name="rocker" pos="0.02 0 0">
        <joint name="rocker" axis="0 1 0" range="-1 1"/>
        <geom type="capsule" fromto="0 0 0 0 0 0.04" size="0.002"/>
      </body>
    </body>
  </worldbody>
  <equality><connect body1="coupler" body2="rocker" anchor="0.02 0 0"/></equality>
  <actuator><position joint="crank"/></actuator>
</mujoco>
)";

TEST(MjcfFile, AFourBarLoopIsClosedAtEveryDofValue) {
  const auto model = loadMjcfFile(writeFile("four_bar.xml", kFourBar));
  ASSERT_EQ(model->dofs.size(), 1u);
  EXPECT_NEAR(model->dofs[0].min, -0.8, 1e-12);
  EXPECT_NEAR(model->dofs[0].max, 0.8, 1e-12);
  Robot robot(model);
  for (const double d : {-0.8, -0.25, 0.0, 0.4, 0.8}) {
    SCOPED_TRACE(d);
    robot.setDofValues(std::vector<double>{d});
    const Transform crank = rotation(Vector3::UnitY(), d);
    const Transform coupler = crank * translation(0, 0, 40) * rotation(Vector3::UnitY(), -d);
    const Transform rocker = translation(20, 0, 0) * rotation(Vector3::UnitY(), d);
    expectPose(robot.linkPose(0, 0), crank);
    expectPose(robot.linkPose(0, 1), coupler, 1e-6);
    expectPose(robot.linkPose(1, 0), rocker, 1e-6);
    // The pinned points meet.
    const Vector3 pin1 = robot.linkPose(0, 1) * Vector3(20, 0, 0);
    const Vector3 pin2 = robot.linkPose(1, 0) * Vector3(0, 0, 40);
    EXPECT_LT((pin1 - pin2).norm(), 1e-6);
  }
}

TEST(MjcfFile, LoadsAsAWorldAndIncludesSplice) {
  writeFile("include/parts.xml", R"(<mujoco>
  <default><geom type="sphere" size="0.01"/></default>
</mujoco>)");
  const fs::path file = writeFile("include/main.xml", R"(<mujoco model="spliced">
  <include file="parts.xml"/>
  <worldbody>
    <body name="base"><geom/>
      <body name="finger" pos="0 0 0.02"><joint name="j" axis="1 0 0" range="0 1"/><geom/></body>
    </body>
  </worldbody>
</mujoco>)");
  const World world = loadAnyFile(file, {});
  ASSERT_EQ(world.robotCount(), 1);
  const RobotModel& model = world.robot(0).model();
  ASSERT_EQ(model.dofs.size(), 1u);  // no actuator: one DOF per joint
  // The default from the included file made the finger a 10 mm sphere.
  double radius = 0.0;
  for (const Vector3& v : model.chains[0].links[0].body->mesh->vertices)
    radius = std::max(radius, v.norm());
  EXPECT_NEAR(radius, 10.0, 1e-9);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* message;  // part of the error
  int line;
};

TEST(MjcfFile, BadFilesNameFileLineAndElement) {
  writeFile("bad/cycle_b.xml", R"(<mujoco>
  <include file="cycle_a.xml"/>
</mujoco>)");
  const BadCase cases[] = {
      {"unknown_class.xml", R"(<mujoco>
  <worldbody>
    <body name="a">
      <geom class="nope" type="sphere" size="0.01"/>
    </body>
  </worldbody>
</mujoco>)",
       "unknown default class 'nope'", 4},
      {"missing_mesh.xml", R"(<mujoco>
  <asset>
    <mesh file="nowhere.stl"/>
  </asset>
  <worldbody><body name="a"><geom type="mesh" mesh="nowhere"/></body></worldbody>
</mujoco>)",
       "mesh 'nowhere'", 3},
      {"cycle_a.xml", R"(<mujoco>
  <include file="cycle_b.xml"/>
</mujoco>)",
       "include cycle", 2},
      {"nan.xml", R"(<mujoco>
  <worldbody>
    <body name="a" pos="nan 0 0"><geom type="sphere" size="0.01"/></body>
  </worldbody>
</mujoco>)",
       "not a finite number", 3},
      {"ball.xml", R"(<mujoco>
  <worldbody>
    <body name="a"><geom type="sphere" size="0.01"/>
      <body name="b"><joint type="ball"/><geom type="sphere" size="0.01"/></body>
    </body>
  </worldbody>
</mujoco>)",
       "ball joint inside a hand", 4},
      {"quadratic.xml", R"(<mujoco>
  <worldbody>
    <body name="a"><geom type="sphere" size="0.01"/>
      <body name="b"><joint name="j1" range="0 1"/><geom type="sphere" size="0.01"/></body>
      <body name="c"><joint name="j2" range="0 1"/><geom type="sphere" size="0.01"/></body>
    </body>
  </worldbody>
  <equality><joint joint1="j2" joint2="j1" polycoef="0 1 0.5 0 0"/></equality>
  <actuator><motor joint="j1"/></actuator>
</mujoco>)",
       "quadratic", 8},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path file = writeFile(std::string("bad/") + c.name, c.text);
    try {
      loadRobotFile(file);
      ADD_FAILURE() << "loaded";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      EXPECT_EQ(e.where().line, c.line) << e.what();
      EXPECT_FALSE(e.where().element.empty()) << e.what();
    }
  }
}
}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// The same palm arch in MJCF: a body with a hinge carrying two finger bodies. No actuators, so
// each joint is a DOF; the arch's joint is repeated in both fingers' chains.
TEST(MjcfFile, ABodyCarryingTwoFingersMovesBoth) {
  const auto model = loadMjcfFile(writeFile("arch.xml", R"(<mujoco model="arch">
  <compiler angle="radian"/>
  <default><geom type="box" size="0.005 0.005 0.02"/><joint axis="0 1 0" range="0 1.5"/></default>
  <worldbody>
    <body name="palm"><geom size="0.04 0.02 0.01"/>
      <body name="arch" pos="-0.02 0 0.02">
        <joint name="arch" axis="0 0 1" range="-0.5 0.5"/><geom size="0.015 0.005 0.005"/>
        <body name="ring" pos="0.01 0 0.03"><joint name="ring"/><geom/></body>
        <body name="little" pos="-0.01 0 0.03"><joint name="little"/><geom/></body>
      </body>
    </body>
  </worldbody>
</mujoco>)"));
  ASSERT_EQ(model->dofs.size(), 3u);
  ASSERT_EQ(model->chains.size(), 2u);
  ASSERT_EQ(model->chains[0].links.size(), 2u);  // arch, ring
  ASSERT_EQ(model->chains[1].links.size(), 1u);  // little (the arch's joint taken along)
  Robot robot(model);
  for (const auto& q : {std::vector<double>{0.4, 0.2, 1.1}, std::vector<double>{-0.45, 1.3, 0.1}}) {
    robot.setDofValues(q);
    const Transform arch = translation(-20, 0, 20) * rotation(Vector3::UnitZ(), q[0]);
    expectPose(robot.linkPose(0, 0), arch);
    expectPose(robot.linkPose(0, 1),
               arch * translation(10, 0, 30) * rotation(Vector3::UnitY(), q[1]));
    expectPose(robot.linkPose(1, 0),
               arch * translation(-10, 0, 30) * rotation(Vector3::UnitY(), q[2]));
  }
}

// MuJoCo collides a mesh geom as its convex hull. An L-shaped prism (the L of 20 x 10 and
// 10 x 20 mm rectangles, 10 mm thick: 4,000 mm^3) has as its hull the L with the triangle
// between its arms filled in (500 mm^2 of outline: 5,000 mm^3), without the L's inner corner.
// The link's mass still comes from the mesh itself (1 g/cm^3 by default: 4 g).
TEST(MjcfFile, AMeshGeomCollidesAsItsConvexHullAsInMujoco) {
  writeFile("l_prism.off", R"(OFF
12 20 0
0 0 0
20 0 0
20 10 0
10 10 0
10 30 0
0 30 0
0 0 10
20 0 10
20 10 10
10 10 10
10 30 10
0 30 10
3 0 2 1
3 0 3 2
3 0 5 3
3 3 5 4
3 6 7 8
3 6 8 9
3 6 9 11
3 9 10 11
3 0 1 7
3 0 7 6
3 1 2 8
3 1 8 7
3 2 3 9
3 2 9 8
3 3 4 10
3 3 10 9
3 4 5 11
3 4 11 10
3 5 0 6
3 5 6 11
)");
  const fs::path file = writeFile("l_hand.xml", R"(<mujoco model="l_hand">
  <asset><mesh name="l" file="l_prism.off" scale="0.001 0.001 0.001"/></asset>
  <worldbody>
    <body name="palm"><geom type="box" size="0.01 0.01 0.01"/>
      <body name="finger" pos="0 0 0.05">
        <joint name="bend" axis="0 1 0" range="0 1"/>
        <geom type="mesh" mesh="l"/>
      </body>
    </body>
  </worldbody>
</mujoco>)");
  const auto hulled = loadMjcfFile(file);
  LoadOptions exact_options;
  exact_options.mjcfMeshHulls = false;
  const auto exact = loadMjcfFile(file, exact_options);
  const BodyModel& hull = *hulled->chains[0].links[0].body;
  const BodyModel& mesh = *exact->chains[0].links[0].body;
  EXPECT_NEAR(computeMassProperties(*hull.mesh).volume, 5000.0, 1e-6);
  EXPECT_NEAR(computeMassProperties(*mesh.mesh).volume, 4000.0, 1e-6);
  EXPECT_EQ(mesh.mesh->triangleCount(), 20u);
  for (const Vector3& v : hull.mesh->vertices)
    EXPECT_FALSE(std::abs(v.x() - 10.0) < 1e-9 && std::abs(v.y() - 10.0) < 1e-9)
        << "the L's inner corner is inside the hull: " << v.transpose();
  EXPECT_NEAR(hull.mass, 4.0, 1e-9);
  EXPECT_NEAR(mesh.mass, 4.0, 1e-9);
}

}  // namespace
}  // namespace graspkit
