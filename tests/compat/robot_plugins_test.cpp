// The robot plugins on GraspIt!'s own robot files: every shared robot loads with the plugin of
// its own type, the collision exclusions GraspIt!'s subclasses add are in force, and the Barrett
// hand's breakaway flexion lets a distal joint close on after its proximal joint has stopped.

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <nlohmann/json.hpp>

#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/plugin/registry.hpp"
#include "quiet_warnings.hpp"
#include "reference.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using test::QuietWarnings;

// The <robot type> attribute, read straight from the file.
std::string typeInFile(const fs::path& file) {
  tinyxml2::XMLDocument doc;
  doc.LoadFile(file.c_str());
  const char* type = doc.RootElement() ? doc.RootElement()->Attribute("type") : nullptr;
  return type ? type : "";
}

int disableCollisionTagsInFile(const fs::path& file) {
  tinyxml2::XMLDocument doc;
  doc.LoadFile(file.c_str());
  int count = 0;
  for (auto* e = doc.RootElement()->FirstChildElement("disableCollision"); e;
       e = e->NextSiblingElement("disableCollision"))
    ++count;
  return count;
}

TEST(RobotPlugins, EverySharedRobotLoadsWithItsOwnTypesPlugin) {
  GRASPKIT_REQUIRE_SHARED();
  QuietWarnings quiet;
  const fs::path data = *test::graspitDataDir();
  const fs::path plugin_dir = fs::path(GRASPKIT_BINARY_DIR) / "lib" / "graspkit" / "plugins";
  int special = 0;
  for (const json& entry : test::referenceJson().at("robot_survey_shared")) {
    if (!entry.at("load_ok").get<bool>()) continue;
    const fs::path file = data / entry.at("file").get<std::string>();
    SCOPED_TRACE(file.string());
    const std::string type = typeInFile(file);
    const auto model = loadRobotFile(file);
    EXPECT_EQ(model->type, type);
    ASSERT_NE(model->robotType, nullptr);
    EXPECT_EQ(model->robotType, Registry::global().robotType(type));
    const auto from = Registry::global().provenance(FactoryKind::RobotType, type);
    ASSERT_TRUE(from);
    EXPECT_EQ(model->typeProvider, from->describe());
    if (type == "Robot" || type == "Hand") {
      EXPECT_TRUE(from->plugin.empty());
      continue;
    }
    ++special;
    EXPECT_FALSE(from->plugin.empty());
    EXPECT_EQ(fs::canonical(from->file.parent_path()), fs::canonical(plugin_dir));
  }
  EXPECT_GE(special,
            15);  // Barrett, HumanHand x3, McGrip x4, Puma560, Robonaut x4, RobotIQ x2, ...
}

// Robot `file` alone in a world, for collision-rule queries.
World worldWith(const fs::path& file) {
  World world;
  world.addRobot(Robot(loadRobotFile(file)));
  return world;
}

bool excluded(const World& world, LinkRef a, LinkRef b) {
  auto ref = [](LinkRef l) {
    return l.isBase() ? BodyRef::robotBase(0) : BodyRef::robotLink(0, l);
  };
  return !robotRulesAllow(world, ref(a), ref(b));
}

TEST(RobotPlugins, RobonautExcludesThePalmAgainstTheThumbsSecondLink) {
  GRASPKIT_REQUIRE_SHARED();
  QuietWarnings quiet;
  const fs::path file = *test::graspitDataDir() / "models/robots/Robonaut/Robonaut.xml";
  const World world = worldWith(file);
  // The file itself names none of these pairs: the exclusion is the plugin's.
  EXPECT_EQ(static_cast<int>(world.robot(0).model().disabledCollisions.size()),
            disableCollisionTagsInFile(file) + 1);
  EXPECT_TRUE(excluded(world, LinkRef{}, LinkRef{0, 1}));
  EXPECT_FALSE(excluded(world, LinkRef{}, LinkRef{1, 1}));  // other fingers still collide
}

TEST(RobotPlugins, ShadowExcludesItsTwoOverlappingPairs) {
  GRASPKIT_REQUIRE_SHARED();
  QuietWarnings quiet;
  const fs::path file = *test::graspitDataDir() / "models/robots/ShadowHand/ShadowHandSimple.xml";
  const World world = worldWith(file);
  EXPECT_EQ(static_cast<int>(world.robot(0).model().disabledCollisions.size()),
            disableCollisionTagsInFile(file) + 2);
  EXPECT_TRUE(excluded(world, LinkRef{}, LinkRef{4, 1}));
  EXPECT_TRUE(excluded(world, LinkRef{1, 0}, LinkRef{0, 0}));
  EXPECT_FALSE(excluded(world, LinkRef{2, 0}, LinkRef{1, 0}));
}

// A 20 mm cube centred at `centre`, as an obstacle.
Body cubeAt(const Vector3& centre) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.emplace_back((i & 1) ? 10 : -10, (i & 2) ? 10 : -10, (i & 4) ? 10 : -10);
  // Outward counter-clockwise faces of the cube with vertex bits (x, y, z).
  mesh->triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  auto model = std::make_shared<BodyModel>();
  model->name = "block";
  model->mesh = mesh;
  Body body;
  body.model = model;
  body.kind = BodyKind::Obstacle;
  body.name = "block";
  Transform pose = Transform::Identity();
  pose.translation() = centre;
  body.setPose(pose);
  return body;
}

TEST(RobotPlugins, BarrettDistalJointClosesOnAfterTheProximalJointStops) {
  GRASPKIT_REQUIRE_SHARED();
  QuietWarnings quiet;
  World world;
  world.addRobot(
      Robot(loadRobotFile(*test::graspitDataDir() / "models/robots/Barrett/Barrett.xml")));
  ASSERT_EQ(world.robot(0).model().type, "Barrett");
  // Put a block where chain 2's proximal link (link 0) will be when its DOF reaches 0.7 rad:
  // closing sweeps the proximal link into it, well before the distal link can get there.
  {
    World probe = world.clone();
    probe.setDofValues(0, std::vector<double>{0, 0, 0, 0.7});
    const Transform proximal = probe.robot(0).linkPose(2, 0);
    const auto& mesh = *world.robot(0).model().chains[2].links[0].body->mesh;
    Vector3 centroid = Vector3::Zero();
    for (const Vector3& v : mesh.vertices) centroid += v;
    centroid /= static_cast<double>(mesh.vertices.size());
    world.addBody(cubeAt(proximal * centroid));
  }
  const AutoGraspResult result = autoGrasp(world, 0);
  const Robot& hand = world.robot(0);
  // Joints 6 and 7 are chain 2's: theta = d3 + 5 deg and d3 * 0.333333333 + 40 deg (Barrett.xml),
  // the robot's joint values leave the offsets out.
  const double dof = hand.dofValues()[3];
  const double proximal = hand.jointValues()[6];
  const double distal = hand.jointValues()[7];
  EXPECT_LT(proximal, 0.7) << "the proximal joint stopped at the block";
  EXPECT_GT(dof, proximal + 0.2) << "the DOF went on closing after the proximal joint stopped";
  EXPECT_NEAR(distal, dof * 0.333333333, 1e-9) << "the distal joint followed the DOF";
  EXPECT_TRUE(hand.breakaway()[6].engaged);
  EXPECT_NEAR(hand.breakaway()[6].value, proximal, 1e-9);
  // The proximal link rests on the block (touching, not interpenetrating).
  const BodyRef block = BodyRef::body(0);
  const double gap = distance(world, BodyRef::robotLink(0, LinkRef{2, 0}), block).distance;
  EXPECT_GE(gap, 0.0);
  EXPECT_LE(gap, kContactThreshold);
  EXPECT_NE(result.end, MotionEnd::InterpolationError);
}

}  // namespace
}  // namespace graspkit
