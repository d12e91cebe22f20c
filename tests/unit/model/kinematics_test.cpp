// Kinematics against closed forms: the DH frame against its explicit product, planar and
// prismatic arms, DOF coupling and ranges, links consuming joints, the <transform> grammar,
// breakaway joints, the approach frame, robots mounted on robots, world clones, and the
// friction table. Robots are built in code or from small files written at test time.

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

constexpr double kTol = 1e-9;
constexpr double kDeg = M_PI / 180.0;

// ---------------------------------------------------------------------------------------------
// Independent references

// Rz(theta) * Tz(d) * Tx(a) * Rx(alpha), composed from Eigen primitives.
Transform dhReference(double theta, double d, double a, double alpha) {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(theta, Vector3::UnitZ()));
  t.translate(Vector3(0, 0, d));
  t.translate(Vector3(a, 0, 0));
  t.rotate(Eigen::AngleAxisd(alpha, Vector3::UnitX()));
  return t;
}

Transform rotZ(double angle) {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(angle, Vector3::UnitZ()));
  return t;
}

Transform translation(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(x, y, z);
  return t;
}

// The exact rotation by +90 degrees about z.
Matrix3 rz90() {
  Matrix3 r;
  r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  return r;
}

::testing::AssertionResult transformNear(const Transform& actual, const Transform& expected,
                                         double tol = kTol) {
  const double dr = (actual.linear() - expected.linear()).cwiseAbs().maxCoeff();
  const double dt = (actual.translation() - expected.translation()).cwiseAbs().maxCoeff();
  if (dr <= tol && dt <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\nactual:\n"
                                       << actual.matrix() << "\nexpected:\n"
                                       << expected.matrix() << "\n(max rotation error " << dr
                                       << ", translation error " << dt << ")";
}

// ---------------------------------------------------------------------------------------------
// Robots written at test time: <dir>/<name>.xml with <dir>/iv/link.xml and a unit cube.

constexpr const char* kCubeOff =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

constexpr const char* kLinkXml =
    "<root><material>plastic</material><mass>10</mass>"
    "<geometryFile type=\"off\">cube.off</geometryFile></root>\n";

void writeText(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << file;
}

std::string dofXml(char type = 'r', const std::string& extra = "") {
  return std::string("  <dof type=\"") + type +
         "\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort><Kp>1</Kp><Kd>1</Kd>"
         "<draggerScale>1</draggerScale>" +
         extra + "</dof>\n";
}

// A joint; `theta` and `d` are written as given, so one of them holds the DOF expression.
std::string jointXml(const std::string& type, const std::string& theta, const std::string& d,
                     double a, double alpha, double min, double max) {
  return "    <joint type=\"" + type + "\"><theta>" + theta + "</theta><d>" + d + "</d><a>" +
         std::to_string(a) + "</a><alpha>" + std::to_string(alpha) + "</alpha><minValue>" +
         std::to_string(min) + "</minValue><maxValue>" + std::to_string(max) +
         "</maxValue></joint>\n";
}

std::string linkXml(const std::string& type) {
  return "    <link dynamicJointType=\"" + type + "\">link.xml</link>\n";
}

std::string chainXml(const std::string& body) {
  return "  <chain>\n" + body + "  </chain>\n";
}

// Writes a robot file with the given DOFs and chains; returns its path.
fs::path writeRobot(const std::string& name, const std::string& dofs, const std::string& chains) {
  const fs::path dir = test::scratchDir() / name;
  writeText(dir / "iv" / "cube.off", kCubeOff);
  writeText(dir / "iv" / "link.xml", kLinkXml);
  const fs::path file = dir / (name + ".xml");
  writeText(file, "<?xml version=\"1.0\" ?>\n<robot type=\"Hand\">\n  <palm>link.xml</palm>\n" +
                      dofs + chains + "</robot>\n");
  return file;
}

// ---------------------------------------------------------------------------------------------
// Robots built in code.

// One chain of planar revolute joints (alpha 0), each driven by its own DOF, a Revolute link
// per joint. DOF ranges are [-pi, pi].
std::shared_ptr<RobotModel> planarArmModel(const std::vector<double>& lengths,
                                           const std::string& name = "arm") {
  auto model = std::make_shared<RobotModel>();
  model->name = name;
  model->type = "Robot";
  KinematicChain chain;
  for (std::size_t j = 0; j < lengths.size(); ++j) {
    Joint joint;
    joint.a = lengths[j];
    joint.dof = static_cast<int>(j);
    joint.min = -M_PI;
    joint.max = M_PI;
    chain.joints.push_back(joint);
    Link link;
    link.lastJoint = static_cast<int>(j);
    chain.links.push_back(link);
    Dof dof;
    dof.min = -M_PI;
    dof.max = M_PI;
    dof.joints = {static_cast<int>(j)};
    model->dofs.push_back(dof);
  }
  model->chains.push_back(chain);
  return model;
}

// ---------------------------------------------------------------------------------------------

TEST(DenavitHartenberg, IdentityAtZero) {
  EXPECT_TRUE(transformNear(denavitHartenberg(0, 0, 0, 0), Transform::Identity(), 0.0));
}

TEST(DenavitHartenberg, MatchesExplicitProductForRandomParameters) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> length(-200.0, 200.0);
  for (int i = 0; i < 200; ++i) {
    const double theta = angle(rng), d = length(rng), a = length(rng), alpha = angle(rng);
    SCOPED_TRACE(::testing::Message()
                 << "theta " << theta << " d " << d << " a " << a << " alpha " << alpha);
    EXPECT_TRUE(transformNear(denavitHartenberg(theta, d, a, alpha),
                              dhReference(theta, d, a, alpha), 1e-12));
  }
}

TEST(DenavitHartenberg, SingleParameters) {
  // Each parameter alone: a pure rotation or a pure translation.
  EXPECT_TRUE(transformNear(denavitHartenberg(M_PI / 2, 0, 0, 0), rotZ(M_PI / 2), 1e-15));
  EXPECT_TRUE(transformNear(denavitHartenberg(0, 7, 0, 0), translation(0, 0, 7), 0.0));
  EXPECT_TRUE(transformNear(denavitHartenberg(0, 0, 7, 0), translation(7, 0, 0), 0.0));
  // a is measured along the x axis rotated by theta.
  EXPECT_TRUE(transformNear(denavitHartenberg(M_PI / 2, 0, 7, 0),
                            translation(0, 7, 0) * rotZ(M_PI / 2), 1e-14));
}

TEST(Kinematics, PlanarTwoLinkArmInCode) {
  const double a1 = 100, a2 = 50;
  Robot robot(planarArmModel({a1, a2}));
  const double angles[][2] = {{0, 0},      {0.3, -0.7}, {M_PI / 2, M_PI / 2},
                              {-2.0, 1.1}, {3.0, -3.0}, {-M_PI / 3, 2.5}};
  for (const auto& q : angles) {
    SCOPED_TRACE(::testing::Message() << "q = " << q[0] << ", " << q[1]);
    const std::vector<double> values = {q[0], q[1]};
    robot.setDofValues(values);
    const Transform elbow = translation(a1 * std::cos(q[0]), a1 * std::sin(q[0]), 0) * rotZ(q[0]);
    const Transform tip = translation(a1 * std::cos(q[0]) + a2 * std::cos(q[0] + q[1]),
                                      a1 * std::sin(q[0]) + a2 * std::sin(q[0] + q[1]), 0) *
                          rotZ(q[0] + q[1]);
    EXPECT_TRUE(transformNear(robot.linkPose(0, 0), elbow));
    EXPECT_TRUE(transformNear(robot.linkPose(0, 1), tip));
    EXPECT_TRUE(transformNear(robot.chainEndPose(0), tip));
  }
}

TEST(Kinematics, PlanarTwoLinkArmFromFile) {
  const fs::path file = writeRobot("Planar", dofXml() + dofXml(),
                                   chainXml(jointXml("Revolute", "d0", "0", 100, 0, -180, 180) +
                                            jointXml("Revolute", "d1", "0", 50, 0, -180, 180) +
                                            linkXml("Revolute") + linkXml("Revolute")));
  Robot robot(loadRobotFile(file));
  ASSERT_EQ(robot.dofCount(), 2);
  EXPECT_NEAR(robot.model().dofs[0].min, -M_PI, 1e-12);
  EXPECT_NEAR(robot.model().dofs[0].max, M_PI, 1e-12);
  const double angles[][2] = {{0.5, 0.25}, {-1.2, 2.0}, {2.5, -0.4}, {0, M_PI / 2}};
  for (const auto& q : angles) {
    SCOPED_TRACE(::testing::Message() << "q = " << q[0] << ", " << q[1]);
    robot.setDofValues(std::vector<double>{q[0], q[1]});
    const Vector3 tip(100 * std::cos(q[0]) + 50 * std::cos(q[0] + q[1]),
                      100 * std::sin(q[0]) + 50 * std::sin(q[0] + q[1]), 0);
    EXPECT_TRUE(
        transformNear(robot.linkPose(0, 1), translation(tip.x(), tip.y(), 0) * rotZ(q[0] + q[1])));
    EXPECT_TRUE(
        transformNear(robot.linkPose(0, 0),
                      translation(100 * std::cos(q[0]), 100 * std::sin(q[0]), 0) * rotZ(q[0])));
  }
  // The robot's base pose carries the whole chain.
  const Transform base = translation(1, 2, 3) * rotZ(0.5);
  robot.setPose(base);
  robot.setDofValues(std::vector<double>{0.0, 0.0});
  EXPECT_TRUE(transformNear(robot.linkPose(0, 1), base * translation(150, 0, 0)));
}

TEST(Kinematics, PrismaticJointTranslatesAlongZWithOffset) {
  // theta 90 degrees and a = 3 mm are constant; d = DOF value + 5 mm.
  const fs::path file =
      writeRobot("Slider", dofXml(),
                 chainXml(jointXml("Prismatic", "90", "d0+5", 3, 0, 0, 50) + linkXml("Prismatic")));
  Robot robot(loadRobotFile(file));
  // Prismatic limits are millimetres, not degrees.
  EXPECT_DOUBLE_EQ(robot.model().dofs[0].min, 0.0);
  EXPECT_DOUBLE_EQ(robot.model().dofs[0].max, 50.0);
  EXPECT_DOUBLE_EQ(robot.model().chains[0].joints[0].d, 5.0);
  for (double v : {0.0, 12.0, 33.5, 50.0}) {
    SCOPED_TRACE(v);
    robot.setDofValues(std::vector<double>{v});
    EXPECT_DOUBLE_EQ(robot.jointValues()[0], v);  // offset excluded
    // Rz(90) * Tz(v + 5) * Tx(3): the x offset turns into +y.
    EXPECT_TRUE(transformNear(robot.linkPose(0, 0), translation(0, 3, v + 5) * rotZ(M_PI / 2)));
  }
}

class CouplingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // DOF 0 drives joint C through ratio -1; DOF 1 drives joint A (ratio 0.333333333, +40
    // degrees) and joint B (ratio 1). DOF 1's default of 120 degrees is clamped to 90.
    file_ = writeRobot(
        "Coupled", dofXml() + dofXml('r', "<defaultValue>120</defaultValue>"),
        chainXml(jointXml("Revolute", "d1*0.333333333+40", "0", 10, 0, 0, 60) +
                 linkXml("Revolute")) +
            chainXml(jointXml("Revolute", "d1", "0", 10, 0, -10, 90) + linkXml("Revolute")) +
            chainXml(jointXml("Revolute", "d0*-1", "0", 10, 0, -10, 30) + linkXml("Revolute")));
    model_ = loadRobotFile(file_);
  }

  fs::path file_;
  std::shared_ptr<const RobotModel> model_;
};

TEST_F(CouplingTest, ParsesRatioAndOffset) {
  const Joint& a = model_->chains[0].joints[0];
  EXPECT_EQ(a.dof, 1);
  EXPECT_DOUBLE_EQ(a.ratio, 0.333333333);
  EXPECT_NEAR(a.theta, 40 * kDeg, 1e-15);
  const Joint& c = model_->chains[2].joints[0];
  EXPECT_EQ(c.dof, 0);
  EXPECT_DOUBLE_EQ(c.ratio, -1.0);
  EXPECT_DOUBLE_EQ(c.theta, 0.0);
  EXPECT_EQ(model_->dofs[1].joints, (std::vector<int>{0, 1}));
  EXPECT_EQ(model_->dofs[0].joints, (std::vector<int>{2}));
}

TEST_F(CouplingTest, JointValueIsRatioTimesDofAndThetaAddsOffset) {
  Robot robot(model_);
  robot.setDofValues(std::vector<double>{0.1, 0.6});
  const auto q = robot.jointValues();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_NEAR(q[0], 0.6 / 3, 1e-9);  // offset excluded from joint values
  EXPECT_DOUBLE_EQ(q[0], 0.6 * 0.333333333);
  EXPECT_DOUBLE_EQ(q[1], 0.6);
  EXPECT_DOUBLE_EQ(q[2], -0.1);
  // The DH theta is joint value + 40 degrees; a = 10 mm along the rotated x.
  const double theta = 0.6 * 0.333333333 + 40 * kDeg;
  EXPECT_TRUE(
      transformNear(robot.linkPose(0, 0),
                    translation(10 * std::cos(theta), 10 * std::sin(theta), 0) * rotZ(theta)));
  EXPECT_TRUE(transformNear(robot.linkPose(2, 0),
                            translation(10 * std::cos(-0.1), 10 * std::sin(-0.1), 0) * rotZ(-0.1)));
}

TEST_F(CouplingTest, DofRangeIsIntersectionOfJointRangesOverRatio) {
  // DOF 0: joint C limits [-10, 30] degrees over ratio -1 give [-30, 10], ends swapped.
  EXPECT_NEAR(model_->dofs[0].min, -30 * kDeg, 1e-12);
  EXPECT_NEAR(model_->dofs[0].max, 10 * kDeg, 1e-12);
  // DOF 1: joint A gives [0, 60 / 0.333333333] degrees, joint B [-10, 90]; intersection [0, 90].
  EXPECT_NEAR(model_->dofs[1].min, 0.0, 1e-12);
  EXPECT_NEAR(model_->dofs[1].max, 90 * kDeg, 1e-12);
}

TEST_F(CouplingTest, DefaultValueInDegreesIsClampedIntoRange) {
  Robot robot(model_);
  EXPECT_NEAR(robot.dofValues()[1], 90 * kDeg, 1e-12);
  EXPECT_NEAR(robot.dofValues()[0], 0.0, 1e-12);
}

TEST_F(CouplingTest, ClampPolicyClampsIntoRange) {
  Robot robot(model_);
  robot.setDofValues(std::vector<double>{1.0, 2.0}, LimitPolicy::Clamp);
  EXPECT_NEAR(robot.dofValues()[0], 10 * kDeg, 1e-12);
  EXPECT_NEAR(robot.dofValues()[1], 90 * kDeg, 1e-12);
  EXPECT_NEAR(robot.jointValues()[2], -10 * kDeg, 1e-12);
  robot.setDofValues(std::vector<double>{-1.0, -2.0});  // Clamp is the default
  EXPECT_NEAR(robot.dofValues()[0], -30 * kDeg, 1e-12);
  EXPECT_NEAR(robot.dofValues()[1], 0.0, 1e-12);
  robot.setDofValue(1, 5.0);
  EXPECT_NEAR(robot.dofValues()[1], 90 * kDeg, 1e-12);
}

TEST_F(CouplingTest, IgnorePolicyAppliesValuesAsGiven) {
  Robot robot(model_);
  robot.setDofValues(std::vector<double>{1.0, 2.0}, LimitPolicy::Ignore);
  EXPECT_DOUBLE_EQ(robot.dofValues()[0], 1.0);
  EXPECT_DOUBLE_EQ(robot.dofValues()[1], 2.0);
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 2.0);
  EXPECT_DOUBLE_EQ(robot.jointValues()[2], -1.0);
  robot.setDofValue(0, -4.0, LimitPolicy::Ignore);
  EXPECT_DOUBLE_EQ(robot.dofValues()[0], -4.0);
  EXPECT_DOUBLE_EQ(robot.dofValues()[1], 2.0);
}

TEST_F(CouplingTest, BadValuesThrowAndLeaveTheRobotUnchanged) {
  Robot robot(model_);
  robot.setDofValues(std::vector<double>{0.05, 0.5});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(robot.setDofValues(std::vector<double>{nan, 0.1}), Error);
  EXPECT_THROW(robot.setDofValues(std::vector<double>{0.1, inf}, LimitPolicy::Ignore), Error);
  EXPECT_THROW(robot.setDofValues(std::vector<double>{0.1}), Error);
  EXPECT_THROW(robot.setDofValues(std::vector<double>{0.1, 0.2, 0.3}), Error);
  EXPECT_THROW(robot.setDofValue(2, 0.1), Error);
  EXPECT_THROW(robot.setDofValue(-1, 0.1), Error);
  EXPECT_THROW(robot.setDofValue(0, nan), Error);
  EXPECT_DOUBLE_EQ(robot.dofValues()[0], 0.05);
  EXPECT_DOUBLE_EQ(robot.dofValues()[1], 0.5);
}

TEST(Kinematics, LinksConsumeJointsByType) {
  // Chain 0: Revolute (joint 0), Universal (joints 1, 2).
  // Chain 1: Fixed (no joint: the chain base), Revolute (joint 0), Fixed (still joint 0),
  //          Ball (joints 1, 2, 3).
  const fs::path file =
      writeRobot("Consume", dofXml(),
                 chainXml("    <transform><translation>0 0 7</translation></transform>\n" +
                          jointXml("Revolute", "d0", "0", 20, 90, -180, 180) +
                          jointXml("Revolute", "d0*0.5", "5", 10, -90, -180, 180) +
                          jointXml("Revolute", "d0+30", "0", 15, 0, -180, 180) +
                          linkXml("Revolute") + linkXml("Universal")) +
                     chainXml("    <transform><translation>30 0 0</translation></transform>\n" +
                              jointXml("Revolute", "d0", "2", 4, 90, -180, 180) +
                              jointXml("Revolute", "d0", "0", 6, -90, -180, 180) +
                              jointXml("Revolute", "d0", "3", 0, 90, -180, 180) +
                              jointXml("Revolute", "d0", "0", 8, 0, -180, 180) + linkXml("Fixed") +
                              linkXml("Revolute") + linkXml("Fixed") + linkXml("Ball")));
  auto model = loadRobotFile(file);
  ASSERT_EQ(model->chains[0].links.size(), 2u);
  ASSERT_EQ(model->chains[1].links.size(), 4u);
  EXPECT_EQ(model->chains[0].links[1].lastJoint, 2);
  EXPECT_EQ(model->chains[1].links[0].lastJoint, -1);
  EXPECT_EQ(model->chains[1].links[3].lastJoint, 3);

  Robot robot(model);
  const Transform pose = translation(-5, 4, 1) * rotZ(0.3);
  robot.setPose(pose);
  const double v = 0.4;
  robot.setDofValues(std::vector<double>{v});

  const Transform base0 = pose * translation(0, 0, 7);
  const Transform f00 = base0 * dhReference(v, 0, 20, 90 * kDeg);
  const Transform f01 = f00 * dhReference(0.5 * v, 5, 10, -90 * kDeg);
  const Transform f02 = f01 * dhReference(v + 30 * kDeg, 0, 15, 0);
  EXPECT_TRUE(transformNear(robot.linkPose(0, 0), f00));
  EXPECT_TRUE(transformNear(robot.linkPose(0, 1), f02));  // Universal: frame of its 2nd joint

  const Transform base1 = pose * translation(30, 0, 0);
  const Transform f10 = base1 * dhReference(v, 2, 4, 90 * kDeg);
  const Transform f11 = f10 * dhReference(v, 0, 6, -90 * kDeg);
  const Transform f12 = f11 * dhReference(v, 3, 0, 90 * kDeg);
  const Transform f13 = f12 * dhReference(v, 0, 8, 0);
  EXPECT_TRUE(transformNear(robot.linkPose(1, 0), base1));  // Fixed first: the chain base
  EXPECT_TRUE(transformNear(robot.linkPose(1, 1), f10));
  EXPECT_TRUE(transformNear(robot.linkPose(1, 2), f10));  // Fixed: the previous frame
  EXPECT_TRUE(transformNear(robot.linkPose(1, 3), f13));  // Ball: frame of its 3rd joint
  EXPECT_TRUE(transformNear(robot.chainEndPose(1), f13));
}

TEST(Kinematics, JointsConsumedTable) {
  EXPECT_EQ(jointsConsumed(DynamicJointType::Revolute), 1);
  EXPECT_EQ(jointsConsumed(DynamicJointType::Prismatic), 1);
  EXPECT_EQ(jointsConsumed(DynamicJointType::Universal), 2);
  EXPECT_EQ(jointsConsumed(DynamicJointType::Ball), 3);
  EXPECT_EQ(jointsConsumed(DynamicJointType::Fixed), 0);
}

TEST(TransformGrammar, ChainTransformsComposeInDocumentOrder) {
  auto chain = [](const std::string& transform) {
    return chainXml("    <transform>" + transform + "</transform>\n" +
                    jointXml("Revolute", "d0", "0", 0, 0, -180, 180) + linkXml("Revolute"));
  };
  const fs::path file =
      writeRobot("Grammar", dofXml(),
                 chain("<translation>10 0 0</translation><rotation>90 z</rotation>") +
                     chain("<rotation>90 z</rotation><translation>10 0 0</translation>") +
                     chain("<rotationMatrix>0 1 0 -1 0 0 0 0 1</rotationMatrix>") +
                     chain("<fullTransform>(+1 0 0 0)[+1 +2 +3]</fullTransform>") +
                     chain("<fullTransform>(0.7071067811865476 0 0 0.7071067811865476)[0 0 0]"
                           "</fullTransform>") +
                     chain("<rotation>90 x</rotation><translation>0 0 5</translation>") +
                     chain("<rotation>-90 y</rotation><translation>1 0 0</translation>"
                           "<translation>0 2 0</translation>"));
  auto model = loadRobotFile(file);
  ASSERT_EQ(model->chains.size(), 7u);
  Transform rz = Transform::Identity();
  rz.linear() = rz90();

  // translation then rotation: T * R, the translation is not rotated.
  EXPECT_TRUE(transformNear(model->chains[0].base, translation(10, 0, 0) * rz, 1e-12));
  EXPECT_TRUE(model->chains[0].base.translation().isApprox(Vector3(10, 0, 0), 1e-12));
  // rotation then translation: R * T, the translation is rotated into +y.
  EXPECT_TRUE(transformNear(model->chains[1].base, translation(0, 10, 0) * rz, 1e-12));
  // rotationMatrix is column-major: the first three numbers (0 1 0) are column 0, so this is
  // +90 degrees about z (row-major reading would give -90).
  EXPECT_TRUE(transformNear(model->chains[2].base, rz, 1e-12));
  // fullTransform: (w x y z)[x y z].
  EXPECT_TRUE(transformNear(model->chains[3].base, translation(1, 2, 3), 1e-15));
  EXPECT_TRUE(transformNear(model->chains[4].base, rz, 1e-12));  // w first
  // Rx(90) carries z onto -y.
  EXPECT_TRUE(transformNear(
      model->chains[5].base,
      translation(0, -5, 0) * Transform(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX())), 1e-12));
  // Ry(-90) carries x onto +z; two translations add up in the rotated frame.
  EXPECT_TRUE(transformNear(
      model->chains[6].base,
      translation(0, 2, 1) * Transform(Eigen::AngleAxisd(-M_PI / 2, Vector3::UnitY())), 1e-12));

  // With every joint at 0 and a = d = alpha = 0, the link sits at the chain base.
  Robot robot(model);
  robot.setDofValues(std::vector<double>{0.0});
  for (int c = 0; c < 7; ++c) {
    SCOPED_TRACE(c);
    EXPECT_TRUE(transformNear(robot.linkPose(c, 0), model->chains[c].base, 1e-12));
  }
}

TEST(Breakaway, BrokenJointHoldsWhileTheOtherFollowsTheDof) {
  auto model = std::make_shared<RobotModel>();
  model->name = "finger";
  KinematicChain chain;
  for (int j = 0; j < 2; ++j) {
    Joint joint;
    joint.a = 10;
    joint.dof = 0;
    joint.ratio = j == 0 ? 1.0 : 0.5;
    joint.min = -M_PI;
    joint.max = M_PI;
    chain.joints.push_back(joint);
    Link link;
    link.lastJoint = j;
    chain.links.push_back(link);
  }
  model->chains.push_back(chain);
  Dof dof;
  dof.type = DofType::Breakaway;
  dof.min = -2;
  dof.max = 2;
  dof.joints = {0, 1};
  model->dofs.push_back(dof);

  Robot robot(model);
  robot.setDofValues(std::vector<double>{0.8});
  EXPECT_DOUBLE_EQ(robot.jointValues()[0], 0.8);
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 0.4);

  robot.setBreakaway(0, {true, 0.3});
  EXPECT_DOUBLE_EQ(robot.jointValues()[0], 0.3);  // ratio * breakaway value
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 0.4);
  EXPECT_TRUE(robot.breakaway()[0].engaged);
  EXPECT_DOUBLE_EQ(robot.breakaway()[0].value, 0.3);
  EXPECT_FALSE(robot.breakaway()[1].engaged);

  robot.setDofValues(std::vector<double>{1.2});
  EXPECT_DOUBLE_EQ(robot.dofValues()[0], 1.2);
  EXPECT_DOUBLE_EQ(robot.jointValues()[0], 0.3);  // held
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 0.6);  // follows: 0.5 * 1.2
  // Link poses follow the joint values.
  const Transform l0 = translation(10 * std::cos(0.3), 10 * std::sin(0.3), 0) * rotZ(0.3);
  const Transform l1 = l0 * translation(10 * std::cos(0.6), 10 * std::sin(0.6), 0) * rotZ(0.6);
  EXPECT_TRUE(transformNear(robot.linkPose(0, 0), l0));
  EXPECT_TRUE(transformNear(robot.linkPose(0, 1), l1));

  // The second joint breaks away too, with its own ratio applied to its value.
  robot.setBreakaway(1, {true, 1.0});
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 0.5);
  // Releasing restores the coupling.
  robot.setBreakaway(0, {false, 0.0});
  robot.setBreakaway(1, {});
  EXPECT_DOUBLE_EQ(robot.jointValues()[0], 1.2);
  EXPECT_DOUBLE_EQ(robot.jointValues()[1], 0.6);

  EXPECT_THROW(robot.setBreakaway(2, {true, 0.0}), Error);
  EXPECT_THROW(robot.setBreakaway(-1, {true, 0.0}), Error);
}

TEST(ApproachDirection, AlongZIsIdentity) {
  ApproachDirection approach;
  approach.direction = Vector3(0, 0, 1);
  EXPECT_TRUE(transformNear(approach.frame(), Transform::Identity(), 1e-15));
  approach.direction = Vector3(0, 0, 5);  // normalised
  approach.referenceLocation = Vector3(1, 2, 3);
  EXPECT_TRUE(transformNear(approach.frame(), translation(1, 2, 3), 1e-15));
  // The default is the identity.
  EXPECT_TRUE(transformNear(ApproachDirection{}.frame(), Transform::Identity(), 1e-15));
  RobotModel model;
  EXPECT_TRUE(transformNear(model.approachFrame(), Transform::Identity(), 0.0));
}

TEST(ApproachDirection, AlongXUsesWorldYAsSeed) {
  ApproachDirection approach;
  approach.direction = Vector3(2, 0, 0);
  const Matrix3 r = approach.frame().linear();
  // z = X; seed Y: y = z x Y = Z; x = y x z = Y.
  EXPECT_TRUE(r.col(2).isApprox(Vector3::UnitX(), 1e-15));
  EXPECT_TRUE(r.col(1).isApprox(Vector3::UnitZ(), 1e-15));
  EXPECT_TRUE(r.col(0).isApprox(Vector3::UnitY(), 1e-15));
}

TEST(ApproachDirection, GeneralDirectionGivesRightHandedFrame) {
  for (const Vector3& d : {Vector3(1, 2, 3), Vector3(-0.2, 0.1, -1), Vector3(0.95, 0.1, 0.1),
                           Vector3(-1, -1, 0), Vector3(0.3, -4, 0.2)}) {
    SCOPED_TRACE(::testing::Message() << d.transpose());
    ApproachDirection approach;
    approach.direction = d;
    const Matrix3 r = approach.frame().linear();
    const Vector3 x = r.col(0), y = r.col(1), z = r.col(2);
    EXPECT_TRUE(z.isApprox(d.normalized(), 1e-12));
    EXPECT_NEAR(x.norm(), 1.0, 1e-12);
    EXPECT_NEAR(y.norm(), 1.0, 1e-12);
    EXPECT_NEAR(x.dot(z), 0.0, 1e-12);
    EXPECT_NEAR(y.dot(z), 0.0, 1e-12);
    EXPECT_NEAR(x.dot(y), 0.0, 1e-12);
    EXPECT_TRUE(x.cross(y).isApprox(z, 1e-12));  // right-handed
    // x lies in the plane of z and the seed, on the seed's side.
    const Vector3 seed = std::abs(z.x()) > 0.9 ? Vector3::UnitY() : Vector3::UnitX();
    EXPECT_NEAR(x.dot(z.cross(seed)), 0.0, 1e-12);
    EXPECT_GT(x.dot(seed), 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// Worlds

class WorldTest : public ::testing::Test {
 protected:
  void SetUp() override {
    arm_ = planarArmModel({a1_, a2_}, "parent");
    world_.addRobot(Robot(arm_));
    world_.addRobot(Robot(planarArmModel({20}, "child")));
    world_.addRobot(Robot(planarArmModel({5}, "grandchild")));
    offset_ = translation(0, 0, 5) * Transform(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX()));
  }

  Connection connection(int parent, int chain, int child, Transform offset) {
    Connection c;
    c.parentRobot = parent;
    c.parentChain = chain;
    c.childRobot = child;
    c.offset = offset;
    return c;
  }

  Transform armTip(double q1, double q2) const {
    return translation(a1_ * std::cos(q1) + a2_ * std::cos(q1 + q2),
                       a1_ * std::sin(q1) + a2_ * std::sin(q1 + q2), 0) *
           rotZ(q1 + q2);
  }

  const double a1_ = 100, a2_ = 50;
  std::shared_ptr<RobotModel> arm_;
  World world_;
  Transform offset_;
};

TEST_F(WorldTest, ChildFollowsParentChainEnd) {
  world_.connect(connection(0, 0, 1, offset_));
  // Connecting places the child at once.
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), armTip(0, 0) * offset_));

  const std::vector<double> q = {0.4, -1.1};
  world_.setDofValues(0, q);
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), world_.robot(0).chainEndPose(0) * offset_));
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), armTip(q[0], q[1]) * offset_));
  EXPECT_TRUE(transformNear(world_.mountPose(world_.connections()[0]), world_.robot(1).pose()));

  const Transform base = translation(10, -20, 30) * rotZ(-0.7);
  world_.setRobotPose(0, base);
  EXPECT_TRUE(transformNear(world_.robot(0).pose(), base));
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), base * armTip(q[0], q[1]) * offset_));
}

TEST_F(WorldTest, PoseAndDofValuesAtOncePlaceTheArmAndItsMount) {
  world_.connect(connection(0, 0, 1, offset_));
  const Transform base = translation(-5, 40, 12) * rotZ(0.3);
  const std::vector<double> q = {-0.6, 1.3};
  world_.setRobotPoseAndDofValues(0, base, q);
  // The planar arm's closed form, under the new base, and the mounted child follows.
  EXPECT_TRUE(transformNear(world_.robot(0).pose(), base));
  EXPECT_TRUE(transformNear(world_.robot(0).chainEndPose(0), base * armTip(q[0], q[1])));
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), base * armTip(q[0], q[1]) * offset_));
  // The same link poses, bit for bit, as the pose then the values.
  World apart = world_.clone();
  apart.setRobotPose(0, translation(1, 2, 3));
  apart.setRobotPose(0, base);
  apart.setDofValues(0, q);
  EXPECT_EQ(apart.robot(0).linkPoses()[0][1].matrix(), world_.robot(0).linkPoses()[0][1].matrix());
  EXPECT_EQ(apart.robot(1).pose().matrix(), world_.robot(1).pose().matrix());
  // Bad values change nothing, not even the pose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(
      world_.setRobotPoseAndDofValues(0, Transform::Identity(), std::vector<double>{nan, 0}),
      Error);
  EXPECT_THROW(world_.setRobotPoseAndDofValues(0, Transform::Identity(), std::vector<double>{0}),
               Error);
  EXPECT_TRUE(transformNear(world_.robot(0).pose(), base));
  EXPECT_TRUE(transformNear(world_.robot(0).chainEndPose(0), base * armTip(q[0], q[1])));
}

TEST_F(WorldTest, GrandchildFollowsThroughTwoMounts) {
  world_.connect(connection(0, 0, 1, offset_));
  const Transform offset2 = translation(1, 2, 3);
  world_.connect(connection(1, 0, 2, offset2));
  world_.setDofValues(1, std::vector<double>{0.5});
  world_.setDofValues(0, std::vector<double>{-0.3, 0.9});
  const Transform child = armTip(-0.3, 0.9) * offset_;
  const Transform childTip =
      child * translation(20 * std::cos(0.5), 20 * std::sin(0.5), 0) * rotZ(0.5);
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), child));
  EXPECT_TRUE(transformNear(world_.robot(2).pose(), childTip * offset2));
}

TEST_F(WorldTest, ConnectRejectsBadConnections) {
  EXPECT_THROW(world_.connect(connection(0, 1, 1, offset_)), Error);   // arm has chain 0 only
  EXPECT_THROW(world_.connect(connection(0, -1, 1, offset_)), Error);  // negative chain
  EXPECT_THROW(world_.connect(connection(0, 0, 0, offset_)), Error);   // self-mount
  EXPECT_THROW(world_.connect(connection(0, 0, 3, offset_)), Error);   // no robot 3
  EXPECT_THROW(world_.connect(connection(5, 0, 1, offset_)), Error);   // no robot 5
  EXPECT_TRUE(world_.connections().empty());

  world_.connect(connection(0, 0, 1, offset_));
  EXPECT_THROW(world_.connect(connection(2, 0, 1, offset_)), Error);  // child mounted twice
  world_.connect(connection(1, 0, 2, offset_));
  EXPECT_THROW(world_.connect(connection(2, 0, 0, offset_)), Error);  // 0 -> 1 -> 2 -> 0
  EXPECT_THROW(world_.connect(connection(1, 0, 0, offset_)), Error);  // 0 -> 1 -> 0
  EXPECT_EQ(world_.connections().size(), 2u);
}

TEST_F(WorldTest, CloneIsIndependentAndSharesModels) {
  world_.connect(connection(0, 0, 1, offset_));
  auto body_model = std::make_shared<BodyModel>();
  body_model->name = "box";
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0)};
  mesh->triangles = {{0, 1, 2}};
  body_model->mesh = mesh;
  Body body;
  body.model = body_model;
  body.kind = BodyKind::Graspable;
  world_.addBody(body);

  const std::vector<double> q = {0.2, 0.3};
  world_.setDofValues(0, q);
  const Transform child_before = world_.robot(1).pose();

  World copy = world_.clone();
  copy.setDofValues(0, std::vector<double>{-1.0, 1.5});
  copy.setRobotPose(0, translation(5, 5, 5));
  copy.bodies()[0].setPose(translation(0, 0, 100));

  EXPECT_DOUBLE_EQ(world_.robot(0).dofValues()[0], 0.2);
  EXPECT_DOUBLE_EQ(world_.robot(0).dofValues()[1], 0.3);
  EXPECT_TRUE(transformNear(world_.robot(0).pose(), Transform::Identity(), 0.0));
  EXPECT_TRUE(transformNear(world_.robot(1).pose(), child_before, 0.0));
  EXPECT_TRUE(transformNear(world_.bodies()[0].pose, Transform::Identity(), 0.0));
  EXPECT_TRUE(
      transformNear(copy.robot(1).pose(), translation(5, 5, 5) * armTip(-1.0, 1.5) * offset_));

  // Heavy parts are shared, not copied.
  EXPECT_EQ(copy.robot(0).modelPtr().get(), world_.robot(0).modelPtr().get());
  EXPECT_EQ(copy.robot(0).modelPtr().get(), arm_.get());
  EXPECT_EQ(copy.bodies()[0].model.get(), world_.bodies()[0].model.get());
  EXPECT_EQ(copy.bodies()[0].model->mesh.get(), mesh.get());
}

// ---------------------------------------------------------------------------------------------
// Materials

TEST(Material, StaticFrictionIsSymmetric) {
  for (std::size_t i = 0; i < kMaterialCount; ++i) {
    for (std::size_t j = 0; j < kMaterialCount; ++j) {
      const auto a = static_cast<Material>(i), b = static_cast<Material>(j);
      EXPECT_DOUBLE_EQ(staticFriction(a, b), staticFriction(b, a)) << i << " " << j;
      EXPECT_DOUBLE_EQ(kineticFriction(a, b), kineticFriction(b, a)) << i << " " << j;
      // Kinetic friction never exceeds static friction.
      EXPECT_LE(kineticFriction(a, b), staticFriction(a, b)) << i << " " << j;
    }
  }
}

TEST(Material, FrictionlessGivesZero) {
  for (std::size_t i = 0; i < kMaterialCount; ++i) {
    const auto m = static_cast<Material>(i);
    EXPECT_EQ(staticFriction(Material::Frictionless, m), 0.0);
    EXPECT_EQ(staticFriction(m, Material::Frictionless), 0.0);
    EXPECT_EQ(kineticFriction(Material::Frictionless, m), 0.0);
    EXPECT_EQ(frictionCoefficient(m, Material::Frictionless, true, 100.0), 0.0);
  }
}

TEST(Material, ValuesFromTheSpecTable) {
  EXPECT_DOUBLE_EQ(staticFriction(Material::Glass, Material::Rubber), 1.0);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Glass, Material::Rubber), 0.9);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Rubber, Material::Rubber), 2.0);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Rubber, Material::Rubber), 1.9);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Wood, Material::Stone), 0.6);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Wood, Material::Stone), 0.5);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Stone, Material::Wood), 0.6);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Glass, Material::Glass), 0.2);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Glass, Material::Glass), 0.1);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Metal, Material::Stone), 0.4);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Metal, Material::Stone), 0.3);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Plastic, Material::Plastic), 0.3);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Rubber, Material::Stone), 1.5);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Stone, Material::Rubber), 1.4);
  EXPECT_DOUBLE_EQ(staticFriction(Material::Stone, Material::Stone), 0.7);
  EXPECT_DOUBLE_EQ(kineticFriction(Material::Stone, Material::Stone), 0.6);
}

TEST(Material, NamesRoundTrip) {
  const char* names[] = {"frictionless", "glass", "metal", "plastic", "wood", "rubber", "stone"};
  for (std::size_t i = 0; i < kMaterialCount; ++i) {
    const auto m = static_cast<Material>(i);
    EXPECT_EQ(nameOf(m), names[i]);
    ASSERT_TRUE(valueNamed<Material>(names[i]).has_value()) << names[i];
    EXPECT_EQ(*valueNamed<Material>(names[i]), m);
    EXPECT_EQ(valueNamed<Material>(nameOf(m)), m);
  }
  EXPECT_FALSE(valueNamed<Material>("unobtainium").has_value());
  EXPECT_FALSE(valueNamed<Material>("").has_value());
  EXPECT_FALSE(valueNamed<Material>("Wood").has_value());  // exact, lower-case names
}

TEST(Material, KineticOnlyWhenDynamicAndSliding) {
  const Material a = Material::Glass, b = Material::Rubber;
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, false, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, false, 50.0), 1.0);  // not dynamic
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, true, 0.5), 1.0);    // too slow
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, true, 1.0), 1.0);    // threshold is exclusive
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, true, 1.001), 0.9);
  EXPECT_DOUBLE_EQ(frictionCoefficient(a, b, true, 50.0), 0.9);
  EXPECT_DOUBLE_EQ(frictionCoefficient(Material::Wood, Material::Stone, true, 2.0), 0.5);
}

}  // namespace
}  // namespace graspkit
