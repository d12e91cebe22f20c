#pragma once
// The engine objects a script holds. A world is shared by every body, robot and grasp taken
// from it, so they stay valid (and see its changes) however long the script keeps them.

#include <memory>
#include <optional>
#include <vector>

#include <lua.hpp>

#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/world_session.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/raycast/ray_scene.hpp"

namespace graspkit::lua {

inline constexpr const char* kWorldClass = "graspkit.World";
inline constexpr const char* kBodyClass = "graspkit.Body";
inline constexpr const char* kRobotClass = "graspkit.Robot";
inline constexpr const char* kGraspClass = "graspkit.Grasp";

// The host layer's world handle (world, file, model cache, removals), and the ray scene a
// script's raycasts reuse.
struct ScriptWorld : host::WorldSession {
  // Built on the first raycast and brought up to date before each one.
  std::unique_ptr<RayScene> rays;
  std::size_t raySceneBodyCount = 0;
};
using WorldHandle = std::shared_ptr<ScriptWorld>;

struct BoundBody {
  WorldHandle world;
  BodyRef ref;
  std::size_t removalsSeen = 0;  // of world->removedBodies
};

struct BoundRobot {
  WorldHandle world;
  int index = 0;  // 0-based inside; robot:index() reports index + 1
};

struct BoundGrasp {
  WorldHandle world;
  Grasp grasp;
  std::size_t removalsSeen = 0;  // its bodies are those of the world before later removals
};

void pushWorld(lua_State* L, WorldHandle world);
void pushBody(lua_State* L, const WorldHandle& world, const BodyRef& ref);
void pushRobot(lua_State* L, const WorldHandle& world, int index);
void pushGrasp(lua_State* L, const WorldHandle& world, Grasp grasp);
// A contact as a plain table: body1, body2 (Body objects), point1, point2, normal, distance, mu.
void pushContact(lua_State* L, const WorldHandle& world, const Contact& contact);

ScriptWorld& toWorld(lua_State* L, int arg);
BoundBody& toBody(lua_State* L, int arg);
BoundRobot& toRobot(lua_State* L, int arg);
BoundGrasp& toGrasp(lua_State* L, int arg);
// Brings `body` up to date with the world's removals; false when its own body was removed.
bool followRemovals(BoundBody& body);
// Throws when bodies were removed from the grasp's world since it was measured (its contacts
// would name the wrong bodies).
void checkGraspBodies(const BoundGrasp& grasp);

// A body argument: a Body object of `world`, or the name of one of its bodies or links.
BodyRef toBodyOf(lua_State* L, int arg, const ScriptWorld& world);

}  // namespace graspkit::lua
