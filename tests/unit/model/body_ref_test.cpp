// findBodyRef: a name back to the solid it names, for every kind of solid.

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

}  // namespace
}  // namespace graspkit
