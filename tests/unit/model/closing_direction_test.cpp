// Closing directions (graspkit/model/closing_direction.hpp) on URDF grippers whose answer is known
// by construction: jaws that slide apart as the DOF rises (0 mm is closed: they close towards the
// lower limit) and the same jaws mounted the other way round (0 mm is open). The sign lands in
// Dof::defaultVelocity, which autograsp, the planners and the dynamic close follow; --close
// (LoadOptions::closingDirections) overrides it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/closing_direction.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// Two jaws on prismatic joints along x (the right one mimics the left, mirrored). `sign` +1: the
// jaws start 5 mm apart and open as the DOF rises; -1: they start 85 mm apart and close.
std::string jaws(int sign) {
  const double start = sign > 0 ? 0.0025 : 0.0425;  // each jaw's inner face from the middle, m
  const std::string axis = sign > 0 ? "-1 0 0" : "1 0 0";
  return R"(<?xml version="1.0"?>
<robot name="jaws">
  <link name="palm"><collision><geometry><box size="0.12 0.03 0.01"/></geometry></collision></link>
  <link name="left"><collision><origin xyz="-0.005 0 0.03"/><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <link name="right"><collision><origin xyz="0.005 0 0.03"/><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
  <joint name="l" type="prismatic"><parent link="palm"/><child link="left"/>
    <origin xyz="-)" +
         std::to_string(start) + R"( 0 0.005"/><axis xyz=")" + axis + R"("/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>
  <joint name="r" type="prismatic"><parent link="palm"/><child link="right"/>
    <origin xyz=")" +
         std::to_string(start) + R"( 0 0.005" rpy="0 0 3.141592653589793"/><axis xyz=")" + axis +
         R"("/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/><mimic joint="l"/></joint>
</robot>
)";
}

TEST(ClosingDirection, JawsThatOpenUpwardsCloseTowardsTheLowerLimit) {
  const fs::path folder = test::scratchDir();
  std::ofstream(folder / "opening.urdf") << jaws(+1);
  std::ofstream(folder / "closing.urdf") << jaws(-1);
  const auto opening = loadRobotFile(folder / "opening.urdf");
  const auto closing = loadRobotFile(folder / "closing.urdf");
  EXPECT_EQ(inferClosingDirections(*opening), std::vector<int>{-1});
  EXPECT_EQ(inferClosingDirections(*closing), std::vector<int>{1});
  EXPECT_LT(opening->dofs[0].defaultVelocity, 0.0);
  EXPECT_GT(closing->dofs[0].defaultVelocity, 0.0);
  // The user's word wins, and an index past the DOFs is refused.
  LoadOptions options;
  options.closingDirections[0] = 1;
  EXPECT_GT(loadRobotFile(folder / "opening.urdf", options)->dofs[0].defaultVelocity, 0.0);
  options.closingDirections[1] = -1;
  EXPECT_THROW(loadRobotFile(folder / "opening.urdf", options), Error);
  // Without inference, URDF's old rule: towards the upper limit.
  LoadOptions plain;
  plain.inferClosingDirections = false;
  EXPECT_GT(loadRobotFile(folder / "opening.urdf", plain)->dofs[0].defaultVelocity, 0.0);
}

}  // namespace
}  // namespace graspkit
