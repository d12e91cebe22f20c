// findBodyRef: a name back to the solid it names, for every kind of solid. placeWorldBodies: the
// one walk of the world that collision queries take instead of looking up each body.

#include <gtest/gtest.h>

#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"
#include "quiet_warnings.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

TEST(FindBodyRef, NamesLeadBackToTheirSolids) {
  test::QuietWarnings quiet;
  // The project's default world: a floor, the mug (graspable), the bh8 hand.
  const World world = loadWorldFile(test::modelsDir() / "worlds/default.xml");
  const auto mug = findBodyRef(world, "mug");
  ASSERT_TRUE(mug);
  EXPECT_EQ(*mug, BodyRef::body(1));
  const auto bodies = worldBodies(world);
  int links = 0;
  for (const BodyRef& ref : bodies) {
    const std::string name = bodyName(world, ref);
    const auto found = findBodyRef(world, name);
    ASSERT_TRUE(found) << name;
    EXPECT_EQ(*found, ref) << name;
    links += ref.isLink() ? 1 : 0;
  }
  EXPECT_GT(links, 3);  // the palm and the fingers' links were looked up too
  EXPECT_FALSE(findBodyRef(world, "no such body"));
  EXPECT_FALSE(findBodyRef(world, ""));
}

// Each placed body must be the body worldBodies() names at the same place, with the model and pose
// that the per-ref lookups give: the collision queries trust the walk and look nothing up again.
TEST(PlaceWorldBodies, AgreesWithTheLookupsOfEachBody) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  // A Puma560 carrying a Barrett hand on a mount piece, beside a glass: bodies, two robots'
  // bases and links, and a mount.
  World world = loadWorldFile(*test::graspitDataDir() / "worlds/barrettGlassDyn.xml");
  ASSERT_GE(world.robotCount(), 2);
  // Joints away from their loaded values, so that link poses come from the kinematics.
  std::vector<double> dofs(world.robot(0).dofCount(), 0.3);
  world.setDofValues(0, dofs);

  std::vector<PlacedBody> placed{{BodyRef::body(0), nullptr, {}}};  // a stale entry to be cleared
  placeWorldBodies(world, placed);
  const std::vector<BodyRef> refs = worldBodies(world);
  ASSERT_EQ(placed.size(), refs.size());
  int mounts = 0, links = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const BodyRef& ref = refs[i];
    EXPECT_EQ(placed[i].ref, ref) << i;
    EXPECT_EQ(placed[i].model, &bodyModel(world, ref)) << bodyName(world, ref);
    EXPECT_EQ(placed[i].pose.matrix(), bodyPose(world, ref).matrix()) << bodyName(world, ref);
    mounts += ref.kind == BodyRef::Kind::Mount ? 1 : 0;
    links += ref.isLink() ? 1 : 0;
  }
  EXPECT_EQ(mounts, 1);
  EXPECT_GT(links, 6);  // the arm's links and the hand's
}

}  // namespace
}  // namespace graspkit
