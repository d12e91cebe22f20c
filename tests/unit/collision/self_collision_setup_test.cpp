// The hand setup's self-collision pairs (graspkit/collision/self_collision_setup.hpp) on a URDF
// hand built so that the answer is known: two finger bases are 20 mm cubes turning about their own
// centres 10 mm apart, so they intersect at every posture (the inscribed balls of radius 10 mm
// overlap); two fingertips touch only in the zero posture. The bases' pair must be switched off as
// always in collision, the tips' pair must stay checked, and the switch must be what makes the rest
// posture free. An SRDF beside the file adds its own pairs.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/collision/collision.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// Fingers a and b: bases on y axes through (-5, 0, 20) and (5, 0, 20) mm; each carries a tip
// 60 mm up, reaching towards the other so that the tips overlap by 2 mm at zero.
const char* kOverlappingHand = R"(<?xml version="1.0"?>
<robot name="overlap">
  <link name="palm"><collision><origin xyz="0 0 -0.02"/><geometry><box size="0.1 0.1 0.01"/></geometry></collision></link>
  <link name="a_base"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
  <link name="b_base"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
  <link name="a_tip"><collision><origin xyz="0.013 0 0"/><geometry><box size="0.026 0.01 0.01"/></geometry></collision></link>
  <link name="b_tip"><collision><origin xyz="-0.013 0 0"/><geometry><box size="0.026 0.01 0.01"/></geometry></collision></link>
  <joint name="a" type="revolute"><parent link="palm"/><child link="a_base"/>
    <origin xyz="-0.005 0 0.02"/><axis xyz="0 1 0"/><limit lower="-0.6" upper="0.6" effort="1" velocity="1"/></joint>
  <joint name="b" type="revolute"><parent link="palm"/><child link="b_base"/>
    <origin xyz="0.005 0 0.02"/><axis xyz="0 1 0"/><limit lower="-0.6" upper="0.6" effort="1" velocity="1"/></joint>
  <joint name="a_tip" type="revolute"><parent link="a_base"/><child link="a_tip"/>
    <origin xyz="-0.02 0 0.06"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b_tip" type="revolute"><parent link="b_base"/><child link="b_tip"/>
    <origin xyz="0.02 0 0.06"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";

bool listed(const RobotModel& model, LinkRef a, LinkRef b, std::string* reason = nullptr) {
  for (const CollisionPair& p : model.disabledCollisions) {
    if ((p.first == a && p.second == b) || (p.first == b && p.second == a)) {
      if (reason) *reason = p.reason;
      return true;
    }
  }
  return false;
}

std::vector<CollidingPair> restCollisions(const std::shared_ptr<const RobotModel>& model) {
  World world;
  world.addRobot(Robot(model));
  world.setDofValues(0, std::vector<double>(model->dofs.size(), 0.0));
  return collisionReport(world);
}

TEST(SelfCollisionSetup, OverlappingBasesAreSwitchedOffTouchingTipsStayChecked) {
  const fs::path folder = test::scratchDir();
  const fs::path file = folder / "overlap.urdf";
  std::ofstream(file) << kOverlappingHand;
  LoadOptions off;
  off.switchOffInherentCollisions = false;
  const auto raw = loadUrdfFile(file, off);
  // Without the setup the hand collides with itself at rest: bases and tips.
  EXPECT_EQ(restCollisions(raw).size(), 2u);

  const auto model = loadUrdfFile(file);
  const LinkRef a_base{0, 0}, a_tip{0, 1}, b_base{1, 0}, b_tip{1, 1};
  std::string reason;
  ASSERT_TRUE(listed(*model, a_base, b_base, &reason));
  EXPECT_EQ(reason.rfind("always in collision", 0), 0u) << reason;
  EXPECT_FALSE(listed(*model, a_tip, b_tip)) << "fingertips that meet at rest must stay checked";
  // At rest, only the tips still collide.
  const auto left = restCollisions(model);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].first.link.link, 1);
  EXPECT_EQ(left[0].second.link.link, 1);

  // An SRDF beside the file switches off the tips as well, with its reason.
  std::ofstream(folder / "overlap.srdf")
      << R"(<robot name="overlap"><disable_collisions link1="a_tip" link2="b_tip" reason="Never"/></robot>)";
  const auto with_srdf = loadUrdfFile(file);
  ASSERT_TRUE(listed(*with_srdf, a_tip, b_tip, &reason));
  EXPECT_NE(reason.find("SRDF"), std::string::npos) << reason;
  EXPECT_TRUE(restCollisions(with_srdf).empty());
}

}  // namespace
}  // namespace graspkit
