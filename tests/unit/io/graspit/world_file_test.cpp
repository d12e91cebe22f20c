// World files written and read at test time: the fullTransform text, the breakaway dofValues
// encoding, save -> load -> save stability, atomic saves, <filename> resolution order, saved
// worlds that load from any working folder without the roots they were loaded with, Body XML
// for a mesh elsewhere, and the camera's x y z w quaternion.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/file_reference.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/base/version.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCubeOff =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

void writeText(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << file;
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// A body file `<dir>/<name>.xml` of the given material, with its cube beside it.
fs::path writeBody(const fs::path& dir, const std::string& name, const std::string& material) {
  writeText(dir / "cube.off", kCubeOff);
  const fs::path file = dir / (name + ".xml");
  writeText(file, "<root><material>" + material +
                      "</material><mass>10</mass><geometryFile type=\"off\">cube.off"
                      "</geometryFile></root>\n");
  return file;
}

std::string dofXml(char type, const std::string& extra = "") {
  return std::string("  <dof type=\"") + type +
         "\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort><Kp>1</Kp><Kd>1</Kd>"
         "<draggerScale>1</draggerScale>" +
         extra + "</dof>\n";
}

std::string jointXml(const std::string& theta, double min, double max) {
  return "    <joint type=\"Revolute\"><theta>" + theta +
         "</theta><d>0</d><a>10</a><alpha>0</alpha><minValue>" + std::to_string(min) +
         "</minValue><maxValue>" + std::to_string(max) + "</maxValue></joint>\n";
}

// <root>/robots/Gripper/Gripper.xml: DOF 0 rigid (joint 0, chain 0, [-90, 90] degrees); DOF 1
// breakaway driving joint 1 (ratio 1) and joint 2 (ratio 0.5), both [0, 90] degrees.
fs::path writeGripper(const fs::path& root) {
  const fs::path dir = root / "robots" / "Gripper";
  writeBody(dir / "iv", "link", "rubber");
  const std::string link = "    <link dynamicJointType=\"Revolute\">link.xml</link>\n";
  const fs::path file = dir / "Gripper.xml";
  writeText(file, "<?xml version=\"1.0\" ?>\n<robot type=\"Hand\">\n  <palm>link.xml</palm>\n" +
                      dofXml('r') + dofXml('b', "<breakAwayTorque>0.5</breakAwayTorque>") +
                      "  <chain>\n" + jointXml("d0", -90, 90) + link + "  </chain>\n  <chain>\n" +
                      jointXml("d1", 0, 90) + jointXml("d1*0.5", 0, 90) + link + link +
                      "  </chain>\n</robot>\n");
  return file;
}

Transform randomTransform(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Quaternion q(u(rng), u(rng), u(rng), u(rng));
  q.normalize();
  Transform t = Transform::Identity();
  t.linear() = q.toRotationMatrix();
  t.translation() = Vector3(u(rng), u(rng), u(rng)) * 500.0;
  return t;
}

double transformError(const Transform& a, const Transform& b) {
  return std::max((a.linear() - b.linear()).cwiseAbs().maxCoeff(),
                  (a.translation() - b.translation()).cwiseAbs().maxCoeff());
}

// Reads "(w x y z)[x y z]" by hand, independently of the engine's reader.
Transform parseByHand(const std::string& text) {
  double w, x, y, z, tx, ty, tz;
  char tail = 0;
  const int n = std::sscanf(text.c_str(), "(%lf %lf %lf %lf)[%lf %lf %lf%c", &w, &x, &y, &z, &tx,
                            &ty, &tz, &tail);
  EXPECT_EQ(n, 8) << text;
  EXPECT_EQ(tail, ']') << text;
  Transform t = Transform::Identity();
  t.linear() = Quaternion(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = Vector3(tx, ty, tz);
  return t;
}

LoadOptions hermetic() {
  LoadOptions options;
  options.useEnvironment = false;
  return options;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// ---------------------------------------------------------------------------------------------

TEST(FullTransform, KnownTransformsFormatWithExplicitSigns) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(1, -2, 3.5);
  EXPECT_EQ(formatFullTransform(t), "(+1 +0 +0 +0)[+1 -2 +3.5]");

  // 180 degrees about x: the quaternion (0 1 0 0), w first.
  Transform flip = Transform::Identity();
  flip.linear() = Vector3(1, -1, -1).asDiagonal();
  flip.translation() = Vector3(0, 0, 114.05);
  EXPECT_EQ(formatFullTransform(flip), "(+0 +1 +0 +0)[+0 +0 +114.05]");

  // 90 degrees about z: w = z = sqrt(1/2), x = y = 0.
  Transform rz = Transform::Identity();
  rz.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const Transform back = parseByHand(formatFullTransform(rz));
  EXPECT_LT(transformError(back, rz), 1e-15);
  const std::string text = formatFullTransform(rz);
  EXPECT_EQ(text.substr(0, 5), "(+0.7") << text;
  EXPECT_NE(text.find(" +0 +0 +0.7"), std::string::npos) << text;
}

TEST(FullTransform, RandomTransformsParseBack) {
  const fs::path root = test::scratchDir();
  writeBody(root / "objects", "cube", "wood");
  std::mt19937 rng(2024);
  std::vector<Transform> poses;
  std::string world = "<?xml version=\"1.0\" ?>\n<world>\n";
  for (int i = 0; i < 20; ++i) {
    poses.push_back(randomTransform(rng));
    const std::string text = formatFullTransform(poses.back());
    // By hand: w first, then the translation.
    EXPECT_LT(transformError(parseByHand(text), poses.back()), 1e-12) << text;
    world += "  <obstacle><filename>objects/cube.xml</filename><transform><fullTransform>" + text +
             "</fullTransform></transform></obstacle>\n";
  }
  world += "</world>\n";
  writeText(root / "poses.xml", world);
  // And through the engine's reader.
  const World loaded = loadWorldFile(root / "poses.xml", hermetic());
  ASSERT_EQ(loaded.bodies().size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT(transformError(loaded.bodies()[i].pose, poses[i]), 1e-12) << i;
  }
}

// A quaternion is a direction: (1e200 1e200 0 0) and (1e-200 1e-200 0 0) both name the half
// turn's half about x (90 degrees), though the first's norm overflows a double and the second's
// underflows it. (0 0 0 0) names none and is refused at its element.
TEST(FullTransform, QuaternionScaleDoesNotMatter) {
  const fs::path root = test::scratchDir();
  writeBody(root / "objects", "cube", "wood");
  std::string world = "<?xml version=\"1.0\" ?>\n<world>\n";
  for (const char* q : {"(1e200 1e200 0 0)[0 0 0]", "(1e-200 1e-200 0 0)[0 0 0]"})
    world += std::string("  <obstacle><filename>objects/cube.xml</filename><transform>") +
             "<fullTransform>" + q + "</fullTransform></transform></obstacle>\n";
  world += "</world>\n";
  writeText(root / "scaled.xml", world);
  const World loaded = loadWorldFile(root / "scaled.xml", hermetic());
  const Transform quarterTurn(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitX()));
  for (const Body& body : loaded.bodies()) EXPECT_LT(transformError(body.pose, quarterTurn), 1e-12);
  writeText(root / "zero.xml",
            "<?xml version=\"1.0\" ?>\n<world>\n  <obstacle><filename>objects/cube.xml</filename>"
            "<transform><fullTransform>(0 0 0 0)[0 0 0]</fullTransform></transform></obstacle>\n"
            "</world>\n");
  try {
    loadWorldFile(root / "zero.xml", hermetic());
    ADD_FAILURE() << "a zero quaternion was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("zero.xml:3: <fullTransform>"), std::string::npos)
        << e.what();
  }
}

TEST(DofValues, BreakawayRobotWritesFlagsPerJoint) {
  const fs::path root = test::scratchDir();
  Robot robot(loadRobotFile(writeGripper(root)));
  ASSERT_EQ(robot.dofCount(), 2);
  ASSERT_EQ(robot.model().dofs[1].type, DofType::Breakaway);
  ASSERT_EQ(robot.model().dofs[1].joints, (std::vector<int>{1, 2}));
  EXPECT_DOUBLE_EQ(robot.model().dofs[1].breakAwayTorque, 500.0);  // x1000

  robot.setDofValues(std::vector<double>{0.25, 0.5});
  EXPECT_EQ(formatDofValues(robot), "+0.25 +0.5 0 0");
  robot.setBreakaway(1, {true, 0.375});
  EXPECT_EQ(formatDofValues(robot), "+0.25 +0.5 1 +0.375 0");
  robot.setDofValues(std::vector<double>{-0.5, 0.5});
  robot.setBreakaway(2, {true, 0.125});
  EXPECT_EQ(formatDofValues(robot), "-0.5 +0.5 1 +0.375 1 +0.125");
  robot.setBreakaway(2, {});
  EXPECT_EQ(formatDofValues(robot), "-0.5 +0.5 1 +0.375 0");
}

TEST(DofValues, ReadingBackRestoresBreakawayState) {
  const fs::path root = test::scratchDir();
  Robot robot(loadRobotFile(writeGripper(root)));
  robot.setDofValues(std::vector<double>{-0.5, 0.5});
  robot.setBreakaway(1, {true, 0.375});
  World world;
  world.addRobot(robot, "robots/Gripper/Gripper.xml");
  saveWorldFile(world, root / "saved.xml");

  const World loaded = loadWorldFile(root / "saved.xml", hermetic());
  ASSERT_EQ(loaded.robotCount(), 1);
  const Robot& back = loaded.robot(0);
  EXPECT_EQ(back.dofValues()[0], -0.5);
  EXPECT_EQ(back.dofValues()[1], 0.5);
  EXPECT_FALSE(back.breakaway()[0].engaged);
  EXPECT_TRUE(back.breakaway()[1].engaged);
  EXPECT_EQ(back.breakaway()[1].value, 0.375);
  EXPECT_FALSE(back.breakaway()[2].engaged);
  EXPECT_EQ(back.jointValues()[0], -0.5);
  EXPECT_EQ(back.jointValues()[1], 0.375);  // held where it broke away
  EXPECT_EQ(back.jointValues()[2], 0.25);   // 0.5 * 0.5, following the DOF
}

TEST(DofValues, HandWrittenBreakawayTokens) {
  const fs::path root = test::scratchDir();
  writeGripper(root);
  // 2 DOFs, the second breakaway with two joints, both broken: 6 tokens. Values outside the
  // DOF range load unclamped, as GraspIt! loads them.
  writeText(root / "w.xml",
            "<world><robot><filename>robots/Gripper/Gripper.xml</filename>"
            "<dofValues>+2.5 0.2 1 0.05 1 -0.07</dofValues></robot></world>\n");
  const World world = loadWorldFile(root / "w.xml", hermetic());
  const Robot& robot = world.robot(0);
  EXPECT_EQ(robot.dofValues()[0], 2.5);
  EXPECT_EQ(robot.dofValues()[1], 0.2);
  EXPECT_TRUE(robot.breakaway()[1].engaged);
  EXPECT_EQ(robot.breakaway()[1].value, 0.05);
  EXPECT_TRUE(robot.breakaway()[2].engaged);
  EXPECT_EQ(robot.breakaway()[2].value, -0.07);
  EXPECT_EQ(robot.jointValues()[0], 2.5);
  EXPECT_EQ(robot.jointValues()[1], 0.05);
  EXPECT_EQ(robot.jointValues()[2], 0.5 * -0.07);
}

TEST(WorldFile, SaveLoadSaveIsByteIdentical) {
  const fs::path root = test::scratchDir();
  const fs::path cube_file = writeBody(root / "objects", "cube", "glass");
  auto gripper = loadRobotFile(writeGripper(root));
  std::mt19937 rng(7);

  World world;
  Body obstacle;
  obstacle.model = loadBodyFile(cube_file);
  obstacle.kind = BodyKind::Obstacle;
  obstacle.filename = "objects/cube.xml";
  obstacle.setPose(randomTransform(rng));
  world.addBody(obstacle);
  Body graspable = obstacle;
  graspable.kind = BodyKind::Graspable;
  graspable.name.clear();
  graspable.setPose(randomTransform(rng));
  world.addBody(graspable);

  Robot parent(gripper);
  parent.setDofValues(std::vector<double>{0.3, 0.9});
  parent.setBreakaway(1, {true, 0.6});
  parent.setPose(randomTransform(rng));
  world.addRobot(parent, "robots/Gripper/Gripper.xml");
  Robot child(gripper);
  child.setDofValues(std::vector<double>{-0.2, 0.1});
  world.addRobot(child, "robots/Gripper/Gripper.xml");
  Connection connection;
  connection.parentRobot = 0;
  connection.parentChain = 1;
  connection.childRobot = 1;
  connection.offset = randomTransform(rng);
  connection.mountFilename = "objects/cube.xml";
  connection.mount = obstacle.model;
  world.connect(connection);
  Camera camera;
  camera.position = Vector3(10, -20, 300.5);
  camera.orientation = Quaternion(0.8, 0, 0.6, 0);
  camera.focalDistance = 250;
  world.setCamera(camera);

  saveWorldFile(world, root / "first.xml");
  const World once = loadWorldFile(root / "first.xml", hermetic());
  saveWorldFile(once, root / "second.xml");
  const World twice = loadWorldFile(root / "second.xml", hermetic());
  saveWorldFile(twice, root / "third.xml");
  const std::string second = readText(root / "second.xml");
  EXPECT_EQ(second, readText(root / "third.xml"));

  // What came back is what went in.
  ASSERT_EQ(once.bodies().size(), 2u);
  EXPECT_EQ(once.bodies()[0].kind, BodyKind::Obstacle);
  EXPECT_EQ(once.bodies()[1].kind, BodyKind::Graspable);
  EXPECT_LT(transformError(once.bodies()[0].pose, obstacle.pose), 1e-12);
  EXPECT_LT(transformError(once.bodies()[1].pose, graspable.pose), 1e-12);
  EXPECT_EQ(once.bodies()[0].model->material, Material::Glass);
  ASSERT_EQ(once.robotCount(), 2);
  EXPECT_EQ(once.robot(0).dofValues()[0], 0.3);
  EXPECT_EQ(once.robot(0).dofValues()[1], 0.9);
  EXPECT_TRUE(once.robot(0).breakaway()[1].engaged);
  EXPECT_EQ(once.robot(0).breakaway()[1].value, 0.6);
  EXPECT_LT(transformError(once.robot(0).pose(), parent.pose()), 1e-12);
  ASSERT_EQ(once.connections().size(), 1u);
  const Connection& c = once.connections()[0];
  EXPECT_EQ(c.parentRobot, 0);
  EXPECT_EQ(c.parentChain, 1);
  EXPECT_EQ(c.childRobot, 1);
  EXPECT_EQ(c.mountFilename, "objects/cube.xml");
  EXPECT_LT(transformError(c.offset, connection.offset), 1e-12);
  EXPECT_LT(transformError(once.robot(1).pose(), world.robot(1).pose()), 1e-9);
  ASSERT_TRUE(once.camera().has_value());
  EXPECT_EQ(once.camera()->position, camera.position);
  EXPECT_EQ(once.camera()->focalDistance, 250);
  EXPECT_EQ(once.camera()->orientation.coeffs(), camera.orientation.coeffs());

  // GraspIt!'s layout: header, bodies, robots, connections, camera. Before <world>, a comment
  // records the engine and who provided each robot type (the test hand is a built-in Hand).
  EXPECT_EQ(second.rfind("<?xml version=\"1.0\" ?>\n<!-- saved by graspkit ", 0), 0u) << second;
  EXPECT_NE(second.find("robot types: Hand (built in) -->\n<world>\n"), std::string::npos)
      << second;
  const auto obstacle_at = second.find("<obstacle>");
  const auto graspable_at = second.find("<graspableBody>");
  const auto robot_at = second.find("<robot>");
  const auto connection_at = second.find("<connection>");
  const auto camera_at = second.find("<camera>");
  ASSERT_NE(camera_at, std::string::npos);
  EXPECT_LT(obstacle_at, graspable_at);
  EXPECT_LT(graspable_at, robot_at);
  EXPECT_LT(robot_at, connection_at);
  EXPECT_LT(connection_at, camera_at);
  EXPECT_NE(second.find("<dofValues>+0.3 +0.9 1 +0.6 0</dofValues>"), std::string::npos);
  EXPECT_NE(second.find("<dofValues>-0.2 +0.1 0 0</dofValues>"), std::string::npos);
  EXPECT_NE(second.find("<orientation>+0 +0.6 +0 +0.8</orientation>"), std::string::npos);
}

TEST(WorldFile, SaveIntoMissingDirectoryThrowsAndWritesNothing) {
  const fs::path root = test::scratchDir();
  World world;
  const fs::path target = root / "no" / "such" / "dir" / "world.xml";
  EXPECT_THROW(saveWorldFile(world, target), Error);
  EXPECT_FALSE(fs::exists(root / "no"));
  EXPECT_TRUE(entries(root).empty());
}

TEST(WorldFile, SuccessfulSaveLeavesNoTemporary) {
  const fs::path root = test::scratchDir();
  World world;
  saveWorldFile(world, root / "world.xml");
  saveWorldFile(world, root / "world.xml");  // over an existing file too
  EXPECT_EQ(entries(root), std::vector<std::string>{"world.xml"});
  EXPECT_EQ(
      readText(root / "world.xml"),
      fmt::format("<?xml version=\"1.0\" ?>\n<!-- saved by graspkit {} -->\n<world>\n</world>\n",
                  engineVersion()));
}

// Writes beyond `bytes` fail with EFBIG while it lives (RLIMIT_FSIZE; SIGXFSZ, which would end
// the process, is ignored meanwhile). Root cannot write past it either, unlike a read-only folder.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
};

TEST(WorldFile, FailedWriteKeepsTheOldFile) {
  const fs::path root = test::scratchDir();
  const std::string old_text = "<?xml version=\"1.0\" ?>\n<world>\n<!-- precious -->\n</world>\n";
  writeText(root / "world.xml", old_text);
  World world;
  Camera camera;
  camera.focalDistance = 1;
  world.setCamera(camera);
  {
    const FileSizeLimit limit(16);
    EXPECT_THROW(saveWorldFile(world, root / "world.xml"), Error);
  }
  EXPECT_EQ(readText(root / "world.xml"), old_text);
  EXPECT_EQ(entries(root), std::vector<std::string>{"world.xml"});
}

// The failure says why, in the operating system's words.
TEST(WorldFile, FailedWriteSaysWhy) {
  const fs::path root = test::scratchDir();
  const FileSizeLimit limit(16);
  try {
    saveWorldFile(World{}, root / "world.xml");
    ADD_FAILURE() << "a write past the file size limit succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::strerror(EFBIG)), std::string::npos) << e.what();
  }
}

// A save killed while it writes leaves the old file and nothing else: the text goes to an unnamed
// file that gets its name only once it is whole. The child writes 128 MB and is killed 20 ms in.
TEST(WorldFile, KilledSaveLeavesNoTemporary) {
  const fs::path root = test::scratchDir();
  const std::string old_text = "<?xml version=\"1.0\" ?>\n<world>\n</world>\n";
  writeText(root / "world.xml", old_text);
  const std::string big(128u << 20, 'x');
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      writeFileAtomically(root / "world.xml", big);
    } catch (...) {
    }
    ::_exit(0);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  const std::string now = readText(root / "world.xml");
  EXPECT_TRUE(now == old_text || now.size() == big.size()) << now.size() << " bytes";
  EXPECT_EQ(entries(root), std::vector<std::string>{"world.xml"});
}

// A file its owner made read-only is not replaced (root could, so the check is explicit).
TEST(WorldFile, ReadOnlyTargetIsKept) {
  const fs::path root = test::scratchDir();
  const std::string old_text = "<?xml version=\"1.0\" ?>\n<world>\n</world>\n";
  writeText(root / "world.xml", old_text);
  fs::permissions(root / "world.xml", fs::perms::owner_read | fs::perms::group_read);
  EXPECT_THROW(saveWorldFile(World{}, root / "world.xml"), Error);
  EXPECT_EQ(readText(root / "world.xml"), old_text);
  EXPECT_EQ(entries(root), std::vector<std::string>{"world.xml"});
}

// A name of 250 bytes is valid (the limit is 255); the temporary file must fit beside it.
TEST(WorldFile, LongValidNameSaves) {
  const fs::path root = test::scratchDir();
  const std::string name = std::string(246, 'w') + ".xml";
  saveWorldFile(World{}, root / name);
  EXPECT_EQ(entries(root), std::vector<std::string>{name});
}

TEST(WorldFile, FailedRenameKeepsTheTargetAndLeavesNoTemporary) {
  // The target is a non-empty folder: the rename fails, the folder stays as it was.
  const fs::path root = test::scratchDir();
  writeText(root / "world.xml" / "inside.txt", "keep");
  World world;
  EXPECT_THROW(saveWorldFile(world, root / "world.xml"), Error);
  EXPECT_EQ(entries(root), std::vector<std::string>{"world.xml"});
  EXPECT_EQ(readText(root / "world.xml" / "inside.txt"), "keep");
}

TEST(WorldFile, FilenameResolutionOrder) {
  const fs::path scratch = test::scratchDir();
  const fs::path top = scratch / "top";
  const fs::path worlds = top / "a" / "worlds";
  const fs::path extra_root = scratch / "root";
  writeBody(extra_root / "objects", "box", "metal");
  writeBody(worlds / "objects", "box", "glass");
  writeBody(top / "a" / "objects", "box", "stone");
  writeBody(top / "objects", "box", "rubber");
  const fs::path world_file = worlds / "w.xml";
  writeText(world_file,
            "<?xml version=\"1.0\" ?>\n<world>\n  <graspableBody>\n"
            "    <filename>objects/box.xml</filename>\n  </graspableBody>\n</world>\n");

  auto material = [&](const LoadOptions& options) {
    const World world = loadWorldFile(world_file, options);
    EXPECT_EQ(world.bodies().size(), 1u);
    return world.bodies().at(0).model->material;
  };
  LoadOptions with_root = hermetic();
  with_root.roots = {extra_root};
  EXPECT_EQ(material(with_root), Material::Metal);   // LoadOptions.roots first
  EXPECT_EQ(material(hermetic()), Material::Glass);  // then the world file's folder
  fs::remove_all(worlds / "objects");
  EXPECT_EQ(material(hermetic()), Material::Stone);  // then its parent
  fs::remove_all(top / "a" / "objects");
  EXPECT_EQ(material(hermetic()), Material::Rubber);  // and the parent's parent
  EXPECT_EQ(loadWorldFile(world_file, hermetic()).bodies()[0].model->file,
            top / "objects" / "box.xml");
  fs::remove_all(top / "objects");
  EXPECT_THROW(loadWorldFile(world_file, hermetic()), Error);
  EXPECT_EQ(material(with_root), Material::Metal);

  const auto roots = searchRoots(world_file, with_root);
  ASSERT_GE(roots.size(), 5u);
  EXPECT_EQ(roots[0], extra_root);
  EXPECT_EQ(roots[1], fs::absolute(worlds));
  EXPECT_EQ(roots[2], fs::absolute(top / "a"));
  EXPECT_EQ(roots[3], fs::absolute(top));
  EXPECT_EQ(roots.back(), fs::path("/"));
}

// Runs `body` with the working folder at `folder`, restoring it afterwards.
template <class F>
void runInFolder(const fs::path& folder, F body) {
  const fs::path before = fs::current_path();
  fs::current_path(folder);
  try {
    body();
  } catch (...) {
    fs::current_path(before);
    throw;
  }
  fs::current_path(before);
}

// The text of each <tag> element in `text`, in order.
std::vector<std::string> elementTexts(const std::string& text, const std::string& tag) {
  std::vector<std::string> found;
  const std::string open = "<" + tag + ">", close = "</" + tag + ">";
  for (std::size_t at = text.find(open); at != std::string::npos; at = text.find(open, at)) {
    at += open.size();
    found.push_back(text.substr(at, text.find(close, at) - at));
  }
  return found;
}

// A world that needs a root: lib/models holds the models, src/w.xml names them as GraspIt!
// does (relative to the root) with a graspable box, an obstacle and the breakaway gripper.
struct RootedWorld {
  fs::path top, models, file;
};

RootedWorld rootedWorld() {
  RootedWorld w;
  w.top = test::scratchDir();
  w.models = w.top / "lib" / "models";
  writeBody(w.models / "objects", "box", "glass");
  writeBody(w.models / "obstacles", "floor", "stone");
  writeGripper(w.models);
  w.file = w.top / "src" / "w.xml";
  writeText(w.file,
            "<?xml version=\"1.0\" ?>\n<world>\n"
            "  <obstacle><filename>obstacles/floor.xml</filename><transform><fullTransform>"
            "(+1 +0 +0 +0)[+0 +0 -5]</fullTransform></transform></obstacle>\n"
            "  <graspableBody><filename>objects/box.xml</filename><transform><fullTransform>"
            "(+0.8 +0 +0.6 +0)[+10 +20 +30]</fullTransform></transform></graspableBody>\n"
            "  <robot><filename>robots/Gripper/Gripper.xml</filename>"
            "<dofValues>+0.25 +0.5 0 1 +0.4</dofValues><transform><fullTransform>"
            "(+0 +1 +0 +0)[+0 +0 +190]</fullTransform></transform></robot>\n</world>\n");
  return w;
}

LoadOptions rootedAt(const fs::path& root) {
  LoadOptions options = hermetic();
  options.roots = {root};
  return options;
}

// `reloaded` has the bodies, materials, poses, DOFs, breakaway state and link poses of `world`.
void expectSameWorld(const World& reloaded, const World& world) {
  ASSERT_EQ(reloaded.bodies().size(), world.bodies().size());
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    const Body& a = reloaded.bodies()[i];
    const Body& b = world.bodies()[i];
    EXPECT_EQ(a.kind, b.kind) << i;
    EXPECT_EQ(a.model->material, b.model->material) << i;
    EXPECT_TRUE(fs::equivalent(a.model->file, b.model->file)) << a.model->file;
    EXPECT_LT(transformError(a.pose, b.pose), 1e-12) << i;
  }
  ASSERT_EQ(reloaded.robotCount(), world.robotCount());
  for (int r = 0; r < world.robotCount(); ++r) {
    const Robot& a = reloaded.robot(r);
    const Robot& b = world.robot(r);
    EXPECT_TRUE(fs::equivalent(a.model().file, b.model().file));
    const auto values = [](auto span) { return std::vector<double>(span.begin(), span.end()); };
    EXPECT_EQ(values(a.dofValues()), values(b.dofValues()));
    ASSERT_EQ(a.breakaway().size(), b.breakaway().size());
    for (std::size_t j = 0; j < b.breakaway().size(); ++j) {
      EXPECT_EQ(a.breakaway()[j].engaged, b.breakaway()[j].engaged) << j;
      EXPECT_EQ(a.breakaway()[j].value, b.breakaway()[j].value) << j;
    }
    EXPECT_LT(transformError(a.pose(), b.pose()), 1e-12);
    EXPECT_EQ(values(a.jointValues()), values(b.jointValues()));
  }
}

TEST(WorldPaths, ASavedWorldLoadsFromAnyFolderWithoutItsRoot) {
  const RootedWorld w = rootedWorld();
  EXPECT_THROW(loadWorldFile(w.file, hermetic()), Error);  // it does need its root
  const World world = loadWorldFile(w.file, rootedAt(w.models));
  ASSERT_TRUE(world.robot(0).breakaway()[2].engaged);  // the file's "1 +0.4"

  const fs::path saved = w.top / "out" / "a" / "saved.xml";
  fs::create_directories(saved.parent_path());
  saveWorldFile(world, saved);
  // Named relative to the saved file (the two share w.top): ./ or ../, so never under a root.
  for (const std::string& name : elementTexts(readText(saved), "filename"))
    EXPECT_TRUE(name.starts_with("../../lib/models/")) << name;
  // Loaded with no root, from another working folder, and from the file system's root.
  for (const fs::path& folder : {test::scratchDir(), fs::path("/")}) {
    runInFolder(folder, [&] { expectSameWorld(loadWorldFile(saved, hermetic()), world); });
  }
  // A --root that holds other models of the same names changes nothing: ./ and ../ names are
  // the saved file's own.
  const fs::path decoy = w.top / "decoy";
  writeBody(decoy / "objects", "box", "metal");
  writeBody(decoy / "lib" / "models" / "objects", "box", "metal");
  expectSameWorld(loadWorldFile(saved, rootedAt(decoy)), world);
  // The whole tree moved: the relative names move with it.
  const fs::path moved = test::scratchDir() / "moved";
  fs::rename(w.top, moved);
  const World there = loadWorldFile(moved / "out" / "a" / "saved.xml", hermetic());
  EXPECT_TRUE(fs::equivalent(there.bodies()[1].model->file,
                             moved / "lib" / "models" / "objects" / "box.xml"));
}

TEST(WorldPaths, SavedWhereItSharesNoFolderItNamesModelsAbsolutely) {
  const RootedWorld w = rootedWorld();
  const World world = loadWorldFile(w.file, rootedAt(w.models));
  fs::path other = fs::temp_directory_path() / fmt::format("graspkit-world-paths-{}", getpid());
  fs::create_directories(other);
  const fs::path saved = other / "saved.xml";
  saveWorldFile(world, saved);
  const bool shared = *fs::weakly_canonical(other).relative_path().begin() ==
                      *fs::weakly_canonical(w.models).relative_path().begin();
  for (const std::string& name : elementTexts(readText(saved), "filename"))
    EXPECT_TRUE(shared ? name.starts_with("../") : fs::path(name).is_absolute()) << name;
  runInFolder("/", [&] { expectSameWorld(loadWorldFile(saved, hermetic()), world); });
  fs::remove_all(other);
}

TEST(WorldPaths, ASaveIntoTheModelsTreeKeepsGraspItNames) {
  const RootedWorld w = rootedWorld();
  const World world = loadWorldFile(w.file, rootedAt(w.models));
  const fs::path saved = w.models / "worlds" / "copy.xml";
  fs::create_directories(saved.parent_path());
  saveWorldFile(world, saved);
  EXPECT_EQ(elementTexts(readText(saved), "filename"),
            (std::vector<std::string>{"obstacles/floor.xml", "objects/box.xml",
                                      "robots/Gripper/Gripper.xml"}));
  expectSameWorld(loadWorldFile(saved, hermetic()), world);
}

TEST(WorldPaths, ADotNameIsLookedForBesideTheWorldFileFirst) {
  const RootedWorld w = rootedWorld();
  const fs::path file = w.top / "dot" / "w.xml";
  writeText(file,
            "<?xml version=\"1.0\" ?>\n<world>\n  <graspableBody>\n"
            "    <filename>./objects/box.xml</filename>\n  </graspableBody>\n</world>\n");
  // Not beside the world: found under the root, as names relative to a root always were.
  EXPECT_EQ(loadWorldFile(file, rootedAt(w.models)).bodies().at(0).model->material,
            Material::Glass);
  EXPECT_THROW(loadWorldFile(file, hermetic()), Error);
  // Beside the world: that one, whatever the root holds.
  writeBody(w.top / "dot" / "objects", "box", "rubber");
  EXPECT_EQ(loadWorldFile(file, rootedAt(w.models)).bodies().at(0).model->material,
            Material::Rubber);
}

TEST(WorldPaths, NotFoundListsEachFolderOnce) {
  const RootedWorld w = rootedWorld();
  const fs::path folder = w.file.parent_path();
  LoadOptions options = hermetic();
  // The world's own folder named as a root too, spelled three ways.
  options.roots = {folder, folder / "", folder / "." / ".." / "src", w.models};
  writeText(w.file,
            "<?xml version=\"1.0\" ?>\n<world>\n  <graspableBody>\n"
            "    <filename>objects/missing.xml</filename>\n  </graspableBody>\n</world>\n");
  try {
    loadWorldFile(w.file, options);
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    const std::string message = e.what();
    std::vector<std::string> listed;
    std::istringstream lines(message);
    for (std::string line; std::getline(lines, line);)
      if (line.starts_with("  ")) listed.push_back(fs::path(line.substr(2)).lexically_normal());
    for (auto& path : listed)
      if (path.size() > 1 && path.back() == '/') path.pop_back();
    std::vector<std::string> unique = listed;
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    EXPECT_EQ(unique.size(), listed.size()) << message;
    EXPECT_EQ(std::count(listed.begin(), listed.end(), folder.string()), 1) << message;
    EXPECT_EQ(std::count(listed.begin(), listed.end(), w.models.string()), 1) << message;
    EXPECT_EQ(std::count(listed.begin(), listed.end(), "/"), 1) << message;
  }
}

TEST(BodyXml, AMeshBodyWrittenElsewhereNamesItsMeshFromItsOwnFolder) {
  const fs::path top = test::scratchDir();
  writeText(top / "meshes" / "cube.off", kCubeOff);
  BodyXmlOptions options;
  options.massGrams = 120;
  const fs::path xml = top / "bodies" / "cube.xml";
  writeText(xml, bodyXmlForMesh(top / "meshes" / "cube.off", xml, options));
  EXPECT_NE(readText(xml).find(">../meshes/cube.off</geometryFile>"), std::string::npos)
      << readText(xml);
  const auto beside = loadBodyFile(top / "meshes" / "cube.off");
  runInFolder("/", [&] {
    const auto body = loadBodyFile(xml);
    EXPECT_EQ(body->mass, 120);
    EXPECT_EQ(body->mesh->triangles.size(), beside->mesh->triangles.size());
    EXPECT_EQ(body->cog, beside->cog);
  });
  // Beside the mesh, the bare file name, as GraspIt! writes it.
  EXPECT_NE(bodyXmlForMesh(top / "meshes" / "cube.off", top / "meshes" / "cube.xml", options)
                .find(">cube.off</geometryFile>"),
            std::string::npos);
}

TEST(FileReference, RelativeBelowACommonFolderAbsoluteOtherwise) {
  EXPECT_EQ(fileReference("/work/a/models/mug.xml", "/work/a/out"), "../models/mug.xml");
  EXPECT_EQ(fileReference("/work/a/out/plan_01.xml", "/work/a/out"), "plan_01.xml");
  EXPECT_EQ(fileReference("/work/a/mug.xml", "/tmp/plans"), "/work/a/mug.xml");
  EXPECT_TRUE(isFileRelative("./objects/mug.xml"));
  EXPECT_TRUE(isFileRelative("../models/mug.xml"));
  EXPECT_FALSE(isFileRelative("models/objects/mug.xml"));
  EXPECT_FALSE(isFileRelative("/work/mug.xml"));
  EXPECT_FALSE(isFileRelative(".hidden/mug.xml"));
}

TEST(WorldFile, CameraOrientationIsXyzw) {
  const fs::path root = test::scratchDir();
  writeText(root / "camera.xml",
            "<?xml version=\"1.0\" ?>\n<world>\n  <camera>\n"
            "    <position>1 -2 3</position>\n"
            "    <orientation>0 0 0.6 0.8</orientation>\n"
            "    <focalDistance>42.5</focalDistance>\n  </camera>\n</world>\n");
  const World world = loadWorldFile(root / "camera.xml", hermetic());
  ASSERT_TRUE(world.camera().has_value());
  const Camera& camera = *world.camera();
  EXPECT_EQ(camera.position, Vector3(1, -2, 3));
  EXPECT_EQ(camera.orientation.w(), 0.8);
  EXPECT_EQ(camera.orientation.x(), 0.0);
  EXPECT_EQ(camera.orientation.y(), 0.0);
  EXPECT_EQ(camera.orientation.z(), 0.6);
  EXPECT_EQ(camera.focalDistance, 42.5);

  saveWorldFile(world, root / "saved.xml");
  const std::string text = readText(root / "saved.xml");
  EXPECT_NE(text.find("<position>+1 -2 +3</position>"), std::string::npos) << text;
  EXPECT_NE(text.find("<orientation>+0 +0 +0.6 +0.8</orientation>"), std::string::npos) << text;
  EXPECT_NE(text.find("<focalDistance>+42.5</focalDistance>"), std::string::npos) << text;
}

}  // namespace
}  // namespace graspkit
