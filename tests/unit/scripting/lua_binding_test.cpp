// The graspkit Lua module against independent truths: closed forms for poses, distances and
// rays on the project's own box (60 x 60 x 120 mm) and sphere (r = 40 mm); the C++ API for
// kinematics (the binding must hand the same numbers through); and the error contract (wrong
// types, out-of-range indices and engine errors raise Lua errors that name the script line).

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/lua/script_host.hpp"
#include "graspkit/model/robot.hpp"
#include "lua_api.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

class LuaBinding : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::scratchDir();
    script_ = folder_ / "scenario.lua";
    std::ofstream(script_) << "-- empty: the tests run chunks through runString\n";
  }

  lua::ScriptHost& host() {
    if (!host_) {
      lua::ScriptOptions options;
      options.load.roots = {test::modelsDir()};
      options.load.useEnvironment = false;
      host_ = std::make_unique<lua::ScriptHost>(script_, options);
    }
    return *host_;
  }

  // Runs `code` (which must succeed) and returns the number left in global `result`.
  double number(const std::string& code) {
    const lua::ScriptOutcome outcome = host().runString(code, "check.lua");
    EXPECT_TRUE(outcome.ok) << outcome.message;
    lua_State* L = host().state();
    lua_getglobal(L, "result");
    const double value = lua_tonumber(L, -1);
    EXPECT_TRUE(lua_isnumber(L, -1)) << "result is " << luaL_typename(L, -1);
    lua_pop(L, 1);
    return value;
  }

  bool boolean(const std::string& code) {
    const lua::ScriptOutcome outcome = host().runString(code, "check.lua");
    EXPECT_TRUE(outcome.ok) << outcome.message;
    lua_State* L = host().state();
    lua_getglobal(L, "result");
    EXPECT_TRUE(lua_isboolean(L, -1)) << "result is " << luaL_typename(L, -1);
    const bool value = lua_toboolean(L, -1) != 0;
    lua_pop(L, 1);
    return value;
  }

  // Runs `code`, which must fail, and returns the error message.
  std::string error(const std::string& code) {
    const lua::ScriptOutcome outcome = host().runString(code, "check.lua");
    EXPECT_FALSE(outcome.ok) << "no error from: " << code;
    return outcome.message;
  }

  fs::path folder_;
  fs::path script_;
  std::unique_ptr<lua::ScriptHost> host_;
};

// A box (top face at z = 60) at the origin and a sphere of radius 40 centred at z = 200.
const char* kBoxAndSphere = R"(
  world = graspkit.new_world()
  box = world:add_obstacle("objects/box.xml")
  ball = world:add_object("objects/sphere.xml", graspkit.pose({0, 0, 200}))
)";

TEST_F(LuaBinding, ModuleIsAGlobalAndARequire) {
  EXPECT_TRUE(boolean("result = require('graspkit') == graspkit"));
  EXPECT_TRUE(boolean("result = type(graspkit.version()) == 'string'"));
}

TEST_F(LuaBinding, AxisAngleRotatesAPointAsTheRightHandRuleSays) {
  // A quarter turn about z takes x to y; then the translation.
  const std::string p = "p = graspkit.axis_angle({0, 0, 1}, math.pi / 2, {1, 2, 3}) ";
  EXPECT_NEAR(number(p + "result = graspkit.transform_point(p, {1, 0, 0})[1]"), 1.0, 1e-12);
  EXPECT_NEAR(number(p + "result = graspkit.transform_point(p, {1, 0, 0})[2]"), 3.0, 1e-12);
  EXPECT_NEAR(number(p + "result = graspkit.rotate_vector(p, {1, 0, 0})[2]"), 1.0, 1e-12);
  EXPECT_NEAR(number(p + "result = p.quaternion[1]"), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(number(p + "result = p.quaternion[4]"), std::sqrt(0.5), 1e-12);
}

TEST_F(LuaBinding, ComposeWithTheInverseIsTheIdentity) {
  const std::string p = "p = graspkit.axis_angle({1, 2, 3}, 0.7, {10, -4, 2}) ";
  double t = number(p +
                    "local d, a = graspkit.pose_distance(p * graspkit.inverse(p), "
                    "graspkit.identity()) result = d + a");
  EXPECT_NEAR(t, 0.0, 1e-12);
  t = number(p +
             "local d, a = graspkit.pose_distance(graspkit.compose(graspkit.inverse(p), p), "
             "graspkit.identity()) result = d + a");
  EXPECT_NEAR(t, 0.0, 1e-12);
  // Composition order: (T1 * T2) applied to a point is T1(T2(point)).
  EXPECT_NEAR(number("local a = graspkit.pose({5, 0, 0}) "
                     "local b = graspkit.axis_angle({0, 0, 1}, math.pi) "
                     "result = graspkit.transform_point(a * b, {1, 0, 0})[1]"),
              4.0, 1e-12);
}

TEST_F(LuaBinding, QuaternionsAreNormalisedAndBadPosesRefused) {
  EXPECT_NEAR(number("result = graspkit.pose(nil, {2, 0, 0, 0}).quaternion[1]"), 1.0, 0.0);
  EXPECT_NE(error("graspkit.pose(nil, {0, 0, 0, 0})").find("the quaternion is zero"),
            std::string::npos);
  // Huge components still name their rotation (a half turn about x here), never the identity;
  // infinite ones name none.
  EXPECT_NEAR(number("result = graspkit.pose(nil, {0, 1e308, 0, 0}).quaternion[2]"), 1.0, 1e-15);
  EXPECT_NEAR(number("result = graspkit.pose(nil, {1e300, 1e300, 0, 0}).quaternion[1]"),
              std::sqrt(0.5), 1e-15);
  EXPECT_NE(error("graspkit.pose(nil, {1, math.huge, 0, 0})").find("finite"), std::string::npos);
  const std::string unknown =
      error("graspkit.new_world():add_obstacle('objects/box.xml', {position = {1, 2, 3}})");
  EXPECT_NE(unknown.find("only the keys 'translation' and 'quaternion'"), std::string::npos)
      << unknown;
  const std::string short_list = error("graspkit.pose({1, 2})");
  EXPECT_NE(short_list.find("needs 3 numbers, got 2"), std::string::npos) << short_list;
}

TEST_F(LuaBinding, DistanceBetweenBoxAndSphereIsTheGap) {
  // Gap: 200 - 40 - 60 = 100 mm. The tessellated sphere lies inside the true one, so its
  // distance can only be larger, by at most the tessellation's sagitta (well under 1 mm).
  const double d = number(std::string(kBoxAndSphere) + "result = world:distance(box, ball)");
  EXPECT_GE(d, 100.0 - 1e-6);
  EXPECT_LT(d, 101.0);
  // Names work wherever a body does.
  EXPECT_NEAR(number(std::string(kBoxAndSphere) + "result = world:distance('box', 'sphere')"), d,
              1e-9);
}

TEST_F(LuaBinding, RaysHitTheNearestFaceOrNothing) {
  const std::string setup = kBoxAndSphere;
  // Beside the sphere (|x| > 40), straight down onto the box's top face at z = 60.
  EXPECT_NEAR(number(setup + "result = world:raycast({25, 25, 100}, {0, 0, -1}).distance"), 40.0,
              1e-4);
  EXPECT_TRUE(boolean(setup + "result = world:raycast({25, 25, 100}, {0, 0, -1}).body == box"));
  EXPECT_NEAR(number(setup + "result = world:raycast({25, 25, 100}, {0, 0, -1}).normal[3]"), 1.0,
              1e-6);
  EXPECT_NEAR(number(setup + "result = world:raycast({25, -25, 100}, {0, 0, -1}).point[3]"), 60.0,
              1e-4);
  // Down the sphere's axis: its top at z = 240 (a pole of the tessellation or within a mm).
  const double top = number(setup + "result = world:raycast({0, 0, 500}, {0, 0, -1}).point[3]");
  EXPECT_LE(top, 240.0 + 1e-4);
  EXPECT_GT(top, 239.0);
  // Past both: nil; and max_distance stops short of the box.
  EXPECT_TRUE(boolean(setup + "result = world:raycast({100, 100, 500}, {0, 0, -1}) == nil"));
  EXPECT_TRUE(boolean(
      setup + "result = world:raycast({25, 25, 100}, {0, 0, -1}, {max_distance = 39}) == nil"));
}

TEST_F(LuaBinding, CollisionFollowsThePoses) {
  const std::string setup = kBoxAndSphere;
  EXPECT_FALSE(boolean(setup + "result = world:collides()"));
  // Sphere centre at z = 90: it reaches down to 50, into the box (top at 60).
  EXPECT_TRUE(
      boolean(setup + "ball:set_pose(graspkit.pose({0, 0, 90})) result = world:collides()"));
  // Pairs come in the world's body order: the box was added first.
  EXPECT_TRUE(boolean(setup +
                      "ball:set_pose(graspkit.pose({0, 0, 90})) local pairs = world:collisions() "
                      "result = #pairs == 1 and pairs[1][1] == box and pairs[1][2] == ball"));
  EXPECT_TRUE(boolean(setup + "ball:set_pose(graspkit.pose({0, 0, 90})) "
                              "result = world:collides(ball, box) and world:collides(ball)"));
}

TEST_F(LuaBinding, RobotDofsAndLinkPosesMatchTheCppApi) {
  // The same robot file through C++: the binding must pass the same numbers through.
  const fs::path file = test::modelsDir() / "robots" / "bh8" / "bh8.xml";
  Robot robot(loadRobotFile(file));
  const std::vector<double> dofs = {0.3, 0.5, 0.7, 0.9};
  robot.setDofValues(dofs);
  const std::string setup =
      "world = graspkit.new_world() hand = world:add_robot('robots/bh8/bh8.xml') "
      "hand:set_dofs({0.3, 0.5, 0.7, 0.9}) poses = hand:link_poses() ";
  EXPECT_EQ(number(setup + "result = hand:dof_count()"), robot.dofCount());
  EXPECT_EQ(number(setup + "result = #poses"), static_cast<double>(robot.linkPoses().size()));
  for (std::size_t c = 0; c < robot.linkPoses().size(); ++c) {
    for (std::size_t l = 0; l < robot.linkPoses()[c].size(); ++l) {
      const Transform& expected = robot.linkPoses()[c][l];
      for (int i = 0; i < 3; ++i) {
        const std::string code = setup + "result = poses[" + std::to_string(c + 1) + "][" +
                                 std::to_string(l + 1) + "].translation[" + std::to_string(i + 1) +
                                 "]";
        EXPECT_NEAR(number(code), expected.translation()[i], 1e-9) << c << " " << l;
      }
    }
  }
  for (int d = 0; d < robot.dofCount(); ++d) {
    const std::string i = std::to_string(d + 1);
    EXPECT_EQ(number(setup + "result = hand:dof_limits()[" + i + "].max"),
              robot.model().dofs[d].max);
  }
}

TEST_F(LuaBinding, BadArgumentsRaiseWithTheScriptLine) {
  const std::string setup =
      "world = graspkit.new_world() hand = world:add_robot('robots/bh8/bh8.xml')\n";
  std::string message = error(setup + "hand:set_dofs({1, 2, 3})");
  EXPECT_NE(message.find("check.lua:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("bad argument #1 to 'set_dofs'"), std::string::npos) << message;
  EXPECT_NE(message.find("4 DOF values expected"), std::string::npos) << message;

  message = error(setup + "hand:set_pose(graspkit.pose({1e300, 0, 0}))");
  EXPECT_NE(message.find("the translation lies past 1e9 mm"), std::string::npos) << message;
  message = error(setup + "hand:set_dofs({0, 0/0, 0, 0})");
  EXPECT_NE(message.find("element 2 is not a finite number"), std::string::npos) << message;
  message = error(setup + "world:robot(2)");
  EXPECT_NE(message.find("robot index 2 out of range (the world has 1)"), std::string::npos)
      << message;
  message = error(setup + "world:robot(0)");
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
  message = error(setup + "hand:link(4, 1)");
  EXPECT_NE(message.find("chain 4 out of range (the robot has 3)"), std::string::npos) << message;
  message = error(setup + "hand:link(1, 1):set_pose(graspkit.identity())");
  EXPECT_NE(message.find("move its robot instead"), std::string::npos) << message;
  message = error(setup + "hand:autograsp({sped = 2})");
  EXPECT_NE(message.find("unknown option 'sped'"), std::string::npos) << message;
  message = error(setup + "world.robot('x', 1)");
  EXPECT_NE(message.find("World expected, got string"), std::string::npos) << message;
  message = error(setup + "hand:grasp(world:clone():add_obstacle('objects/box.xml'))");
  EXPECT_NE(message.find("belongs to another world"), std::string::npos) << message;
}

TEST_F(LuaBinding, EngineErrorsCarryTheEnginesMessage) {
  std::string message = error("graspkit.load_world('objects/no_such_file.xml')");
  EXPECT_NE(message.find("check.lua:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("no_such_file.xml"), std::string::npos) << message;
  // A malformed world file: the engine names the file and line.
  std::ofstream(folder_ / "broken.xml") << "<world>\n  <obstacle>\n</world>\n";
  message = error("graspkit.load_world('" + (folder_ / "broken.xml").string() + "')");
  EXPECT_NE(message.find("broken.xml:"), std::string::npos) << message;
}

TEST_F(LuaBinding, CloneIsIndependent) {
  const std::string setup = std::string(kBoxAndSphere) +
                            "copy = world:clone() copy:body('sphere'):set_pose("
                            "graspkit.pose({0, 0, 500})) ";
  EXPECT_NEAR(number(setup + "result = ball:pose().translation[3]"), 200.0, 0.0);
  EXPECT_NEAR(number(setup + "result = copy:body('sphere'):pose().translation[3]"), 500.0, 0.0);
}

TEST_F(LuaBinding, SavedWorldLoadsBackTheSame) {
  const std::string out = (folder_ / "saved.xml").string();
  const std::string code =
      "world = graspkit.new_world() "
      "world:add_object('objects/sphere.xml', graspkit.axis_angle({0, 1, 0}, 0.3, {1, 2, 3})) "
      "local hand = world:add_robot('robots/bh8/bh8.xml', graspkit.pose({0, 0, 150})) "
      "hand:set_dofs({0.1, 0.2, 0.3, 0.4}) world:save('" +
      out + "') again = graspkit.load_world('" + out +
      "') "
      "local d, a = graspkit.pose_distance(again:body('sphere'):pose(), "
      "world:body('sphere'):pose()) "
      "local dofs = again:robot(1):dofs() "
      "result = d + a + math.abs(dofs[4] - 0.4) + math.abs(again:robot(1):pose().translation[3] "
      "- 150)";
  EXPECT_NEAR(number(code), 0.0, 1e-5);  // the file keeps 6 significant digits or more
}

TEST_F(LuaBinding, JsonRoundTrips) {
  EXPECT_TRUE(
      boolean("local t = graspkit.json_decode(graspkit.json_encode({a = {1, 2.5, 'x'}, b = true})) "
              "result = t.a[1] == 1 and t.a[2] == 2.5 and t.a[3] == 'x' and t.b == true"));
  EXPECT_NE(error("graspkit.json_encode({x = 0/0})").find("JSON cannot hold"), std::string::npos);
  EXPECT_NE(error("graspkit.json_decode('{')").find("json_decode"), std::string::npos);
  // An indent repeats per level: a huge one is refused before any text is built.
  EXPECT_NE(error("graspkit.json_encode({{{1}}}, {indent = 2147483647})").find("'indent'"),
            std::string::npos);
  EXPECT_TRUE(boolean("result = graspkit.json_encode({1}, {indent = 2}) == '[\\n  1\\n]'"));
}

TEST_F(LuaBinding, PluginsListTheRobotPluginsAndTheSandboxGuardsLoading) {
  EXPECT_TRUE(boolean(
      "result = false for _, p in ipairs(graspkit.plugins()) do "
      "  for _, what in ipairs(p.provides) do "
      "    if what.kind == 'robot type' and what.name == 'Barrett' then result = p.loaded end "
      "  end "
      "end"));
  const fs::path good = fs::path(GRASPKIT_PLUGIN_CORPUS_DIR) / "good" / "good.so";
  lua::ScriptOptions options;
  options.sandbox.allowRead = {good.parent_path()};
  lua::ScriptHost sandboxed(script_, options);
  const lua::ScriptOutcome refused =
      sandboxed.runString("graspkit.load_plugin('" + good.string() + "')", "check.lua");
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.message.find("plugin search path"), std::string::npos) << refused.message;
}

// A C++ object in userdata is destroyed once, and only as its own type: __gc called again, or on
// another class's object, or on a number, does nothing; a destroyed object is refused by name.
TEST(LuaObjects, DestroyIsOnceAndTypeChecked) {
  using namespace graspkit::lua;
  lua_State* L = luaL_newstate();
  const luaL_Reg none[] = {{nullptr, nullptr}};
  defineClass(L, "test.Text", none, destroyObject<std::string>, nullptr);
  defineClass(L, "test.Number", none, destroyObject<double>, nullptr);
  newObject<std::string>(L, "test.Text", std::string(100, 'x'));  // heap-allocated text
  const int text = lua_gettop(L);
  newObject<double>(L, "test.Number", 2.5);
  const int number = lua_gettop(L);
  auto destroy = [&](lua_CFunction gc, int arg) {
    lua_pushcfunction(L, gc);
    lua_pushvalue(L, arg);
    ASSERT_EQ(lua_pcall(L, 1, 0, 0), LUA_OK);
  };
  destroy(destroyObject<double>, text);  // a Text is no double: untouched
  EXPECT_EQ(toObject<std::string>(L, text, "test.Text", "Text"), std::string(100, 'x'));
  destroy(destroyObject<std::string>, text);
  destroy(destroyObject<std::string>,
          text);  // a second time: nothing (ASan would see a double free)
  EXPECT_EQ(testObject<std::string>(L, text, "test.Text"), nullptr);
  try {
    toObject<std::string>(L, text, "test.Text", "Text");
    ADD_FAILURE() << "a destroyed object was accepted";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("destroyed"), std::string::npos) << e.what();
  }
  lua_pushnumber(L, 7.0);
  destroy(destroyObject<std::string>, lua_gettop(L));  // not userdata at all
  EXPECT_EQ(toObject<double>(L, number, "test.Number", "Number"), 2.5);
  lua_close(L);  // collects both: the destroyed Text is not destroyed again
}

}  // namespace
}  // namespace graspkit
