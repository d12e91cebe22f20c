// graspkit.load_world, graspkit.new_world and the World class: building worlds, looking things
// up, saving, and the world-wide queries (contacts, collision, distance, rays).

#include <variant>

#include <fmt/format.h>

#include "bound_objects.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/simulation_task.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/render/render.hpp"
#include "lua_api.hpp"
#include "module.hpp"
#include "script_context.hpp"

namespace graspkit::lua {
namespace {

WorldHandle& toWorldHandle(lua_State* L, int arg) {
  return toObject<WorldHandle>(L, arg, kWorldClass, "World");
}

// The load options of `graspkit run`'s flags, with what the options table at `arg` (may be
// absent) sets for this one load: {palm = LINK, urdf_material = NAME, close = {[dof] = "+"|"-"},
// generic_robots = bool}, dof 0-based as --close counts.
LoadOptions loadOptionsAt(lua_State* L, int arg) {
  LoadOptions load = scriptContext(L).options.load;
  const OptionsTable options(L, arg, {"palm", "urdf_material", "close", "generic_robots"});
  if (options.has("palm")) load.urdfPalm = options.string("palm", "");
  if (options.has("urdf_material"))
    load.urdfMaterial = parseNamed<Material>(options.string("urdf_material", ""), "material");
  load.genericRobotFallback = options.boolean("generic_robots", load.genericRobotFallback);
  if (options.has("close")) {
    lua_getfield(L, arg, "close");
    const int table = lua_gettop(L);
    if (!lua_istable(L, table)) throw ArgumentError(L, arg, "option 'close' must be a table");
    lua_pushnil(L);
    while (lua_next(L, table) != 0) {
      const bool ok =
          lua_isinteger(L, -2) && lua_tointeger(L, -2) >= 0 && lua_type(L, -1) == LUA_TSTRING &&
          (std::string(lua_tostring(L, -1)) == "+" || std::string(lua_tostring(L, -1)) == "-");
      if (!ok)
        throw ArgumentError(L, arg, "option 'close' maps 0-based DOF indices to \"+\" or \"-\"");
      load.closingDirections[static_cast<int>(lua_tointeger(L, -2))] =
          std::string(lua_tostring(L, -1)) == "+" ? 1 : -1;
      lua_pop(L, 1);
    }
    lua_settop(L, table - 1);
  }
  return load;
}

// graspkit.load_world(file [, {palm, urdf_material, close, generic_robots}])
int loadWorld(lua_State* L) {
  ScriptContext& context = scriptContext(L);
  const std::filesystem::path file = context.inputPath(toFileName(L, 1));
  const LoadOptions load = loadOptionsAt(L, 2);
  auto handle = std::make_shared<ScriptWorld>();
  static_cast<host::WorldSession&>(*handle) = host::WorldSession::load(file, load, context.cache);
  pushWorld(L, std::move(handle));
  return 1;
}

int newWorld(lua_State* L) {
  auto handle = std::make_shared<ScriptWorld>();
  handle->cache = scriptContext(L).cache;  // a script's worlds read each file once
  pushWorld(L, std::move(handle));
  return 1;
}

int addBody(lua_State* L, BodyKind kind) {
  ScriptWorld& world = *toWorldHandle(L, 1);
  ScriptContext& context = scriptContext(L);
  const std::filesystem::path file = context.inputPath(toFileName(L, 2));
  const Transform pose = isNone(L, 3) ? Transform::Identity() : toPose(L, 3);
  const int index = world.addBody(file, kind, pose);
  pushBody(L, toWorldHandle(L, 1), BodyRef::body(index));
  return 1;
}

int addObstacle(lua_State* L) {
  return addBody(L, BodyKind::Obstacle);
}

int addObject(lua_State* L) {
  return addBody(L, BodyKind::Graspable);
}

int addRobot(lua_State* L) {
  ScriptWorld& world = *toWorldHandle(L, 1);
  ScriptContext& context = scriptContext(L);
  const std::filesystem::path file = context.inputPath(toFileName(L, 2));
  const Transform pose = isNone(L, 3) ? Transform::Identity() : toPose(L, 3);
  const int index = world.addRobot(file, loadOptionsAt(L, 4), pose);
  pushRobot(L, toWorldHandle(L, 1), index);
  return 1;
}

int save(lua_State* L) {
  ScriptWorld& world = *toWorldHandle(L, 1);
  const std::filesystem::path file = scriptContext(L).outputPath(toFileName(L, 2));
  world.save(file);
  return 0;
}

// world:render{out = "file.png", width = 640, height = 480, camera = "auto", contacts = false,
// samples = 1}: a ray-cast PNG (graspkit render). With contacts, the contacts of the grasp
// subject (graspSubject: the first hand and the first graspable body) are marked. Returns the
// file's path.
int render(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  checkTable(L, 2);
  const OptionsTable options(L, 2, {"out", "width", "height", "camera", "contacts", "samples"});
  if (!options.has("out")) throw Error("world:render: 'out' (the PNG to write) is required");
  const std::filesystem::path file = scriptContext(L).outputPath(options.string("out", ""));
  RenderRequest request;
  request.width = options.integer("width", 640);
  request.height = options.integer("height", 480);
  request.samples = options.integer("samples", 1);
  if (request.width < 1 || request.height < 1)
    throw Error(fmt::format("world:render: a {}x{} picture", request.width, request.height));
  const std::vector<BodyRef> focus = handAndObject(world.world);
  request.camera = namedView(world.world, options.string("camera", "auto"), focus,
                             static_cast<double>(request.width) / request.height);
  const GraspSubject subject = graspSubject(world.world);
  if (options.boolean("contacts", false) && subject.hand && subject.object)
    request.contacts = analyzeGrasp(world.world, *subject.hand, *subject.object).contacts;
  writePng(graspkit::render(world.world, request), file);
  lua_pushstring(L, file.c_str());
  return 1;
}

void pushStepReport(lua_State* L, const StepReport& report) {
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, report.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, report.contacts);
  lua_setfield(L, -2, "contacts");
  lua_pushinteger(L, report.activeContacts);
  lua_setfield(L, -2, "active_contacts");
  lua_pushinteger(L, report.jointLimits);
  lua_setfield(L, -2, "joint_limits");
}

// world:step([dt]) -> {time, contacts, active_contacts, joint_limits}
int stepWorld(lua_State* L) {
  ScriptWorld& world = toWorld(L, 1);
  const double dt = isNone(L, 2) ? kDefaultTimeStep : toNumber(L, 2);
  pushStepReport(L, step(world.world, dt));
  return 1;
}

// world:simulate{seconds = 1, dt = 0.0025, gravity = {x, y, z}, autograsp = false} -> the last
// step's report, with its step count; the host layer's settings and defaults, as `graspkit
// simulate` has them. A simulation that blows up raises its reason.
int simulateWorld(lua_State* L) {
  ScriptWorld& world = toWorld(L, 1);
  const OptionsTable options(L, 2, {"seconds", "dt", "gravity", "autograsp"});
  host::SimulationSettings settings;
  settings.seconds = options.number("seconds", settings.seconds);
  settings.dt = options.number("dt", settings.dt);
  settings.autograsp = options.boolean("autograsp", settings.autograsp);
  if (options.has("gravity")) {
    lua_getfield(L, 2, "gravity");
    settings.gravity = toVector3(L, lua_gettop(L));
    lua_pop(L, 1);
  }
  const host::SimulationOutcome outcome = host::simulateWorld(world.world, settings);
  if (!outcome.completed) throw Error(outcome.stopReason);
  pushStepReport(L, outcome.result.last);
  lua_pushinteger(L, outcome.result.steps);
  lua_setfield(L, -2, "steps");
  lua_pushnumber(L, outcome.result.time);
  lua_setfield(L, -2, "time");
  return 1;
}

// world:validate{seconds = 2}: the grasp the world holds (its first hand closed on its first
// graspable body) labelled as `graspkit validate` labels it -> {held, directions_held,
// settle_seconds, directions = {{direction, held, slip_mm, turn_deg, seconds [, failure]}, ...}}
int validateWorld(lua_State* L) {
  const ScriptWorld& world = toWorld(L, 1);
  const OptionsTable options(L, 2, {"seconds"});
  ValidationRequest request;
  request.seconds = options.number("seconds", request.seconds);
  const ValidationResult result = host::validateWorld(world.world, request);
  lua_createtable(L, 0, 4);
  lua_pushboolean(L, result.held);
  lua_setfield(L, -2, "held");
  lua_pushinteger(L, result.directionsHeld);
  lua_setfield(L, -2, "directions_held");
  lua_pushnumber(L, result.settleSeconds);
  lua_setfield(L, -2, "settle_seconds");
  lua_createtable(L, 6, 0);
  for (int k = 0; k < 6; ++k) {
    const DirectionResult& d = result.directions[k];
    lua_createtable(L, 0, 6);
    lua_pushstring(L, host::kValidationDirections[k].data());
    lua_setfield(L, -2, "direction");
    lua_pushboolean(L, d.held);
    lua_setfield(L, -2, "held");
    lua_pushnumber(L, d.slip);
    lua_setfield(L, -2, "slip_mm");
    lua_pushnumber(L, d.turn * 180.0 / M_PI);
    lua_setfield(L, -2, "turn_deg");
    lua_pushnumber(L, d.seconds);
    lua_setfield(L, -2, "seconds");
    if (!d.failure.empty()) {
      lua_pushstring(L, d.failure.c_str());
      lua_setfield(L, -2, "failure");
    }
    lua_rawseti(L, -2, k + 1);
  }
  lua_setfield(L, -2, "directions");
  return 1;
}

// world:set_gravity{x, y, z} (mm/s^2; {0, 0, 0} is GraspIt!'s world without gravity)
int setGravity(lua_State* L) {
  toWorld(L, 1).world.setGravity(toVector3(L, 2));
  return 0;
}

int gravity(lua_State* L) {
  pushVector3(L, toWorld(L, 1).world.gravity());
  return 1;
}

int worldTime(lua_State* L) {
  lua_pushnumber(L, toWorld(L, 1).world.time());
  return 1;
}

int clone(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  auto copy = std::make_shared<ScriptWorld>();
  static_cast<host::WorldSession&>(*copy) = world.clone();
  pushWorld(L, std::move(copy));
  return 1;
}

int file(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  if (world.file.empty()) {
    lua_pushnil(L);
  } else {
    lua_pushstring(L, world.file.c_str());
  }
  return 1;
}

int bodies(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const int count = static_cast<int>(handle->world.bodies().size());
  lua_createtable(L, count, 0);
  for (int i = 0; i < count; ++i) {
    pushBody(L, handle, BodyRef::body(i));
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

int body(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  toString(L, 2);  // a name, not a Body
  pushBody(L, handle, toBodyOf(L, 2, *handle));
  return 1;
}

int robots(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const int count = handle->world.robotCount();
  lua_createtable(L, count, 0);
  for (int i = 0; i < count; ++i) {
    pushRobot(L, handle, i);
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

int robot(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const World& world = handle->world;
  if (lua_type(L, 2) == LUA_TSTRING) {
    const std::string name = toString(L, 2);
    const std::optional<int> index = world.findRobot(name);
    if (!index) {
      std::string known;
      for (int i = 0; i < world.robotCount(); ++i) {
        known += (known.empty() ? "" : ", ") + world.robot(i).name();
      }
      throw ArgumentError(L, 2,
                          fmt::format("no robot '{}' in the world (robots: {})", name,
                                      known.empty() ? "none" : known));
    }
    pushRobot(L, handle, *index);
    return 1;
  }
  const int index = toInteger(L, 2);
  if (index < 1 || index > world.robotCount()) {
    throw ArgumentError(
        L, 2,
        fmt::format("robot index {} out of range (the world has {})", index, world.robotCount()));
  }
  pushRobot(L, handle, index - 1);
  return 1;
}

// Every pair collision detection looks at, touching within the contact threshold.
int contacts(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const World& world = handle->world;
  const ContactRequest request;
  std::vector<Contact> found;
  for (const BodyPair& pair : nearbyPairs(world, request.threshold)) {
    ContactResult result = findContacts(world, pair.first, pair.second, request);
    found.insert(found.end(), result.contacts.begin(), result.contacts.end());
  }
  lua_createtable(L, static_cast<int>(found.size()), 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    pushContact(L, handle, found[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

// world:collides()      any pair collision detection looks at intersects;
// world:collides(a)     any such pair with body a;
// world:collides(a, b)  the surfaces of a and b intersect (whatever the collision filter says).
int collides(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  bool result = false;
  if (isNone(L, 2)) {
    result = anyCollision(world.world, {});
  } else if (isNone(L, 3)) {
    const BodyRef a = toBodyOf(L, 2, world);
    result = anyCollision(world.world, std::span<const BodyRef>(&a, 1));
  } else {
    result = collide(world.world, toBodyOf(L, 2, world), toBodyOf(L, 3, world));
  }
  lua_pushboolean(L, result);
  return 1;
}

int collisions(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const std::vector<CollidingPair> pairs = collisionReport(handle->world);
  lua_createtable(L, static_cast<int>(pairs.size()), 0);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    lua_createtable(L, 2, 0);
    pushBody(L, handle, pairs[i].first);
    lua_rawseti(L, -2, 1);
    pushBody(L, handle, pairs[i].second);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

// world:distance(a, b) -> distance (mm), closest point on a, closest point on b.
int distance(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  const DistanceResult result =
      graspkit::distance(world.world, toBodyOf(L, 2, world), toBodyOf(L, 3, world));
  lua_pushnumber(L, result.distance);
  pushVector3(L, result.pointOnA);
  pushVector3(L, result.pointOnB);
  return 3;
}

const RayScene& rayScene(ScriptWorld& world) {
  const std::size_t count = worldBodies(world.world).size();
  if (!world.rays || world.raySceneBodyCount != count) {
    world.rays = std::make_unique<RayScene>(world.world);
    world.raySceneBodyCount = count;
  } else {
    world.rays->update(world.world);
  }
  return *world.rays;
}

// world:raycast(origin, direction [, {max_distance = mm}]) -> {body, point, normal, distance}
// or nil when the ray meets nothing.
int raycast(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  Ray ray;
  ray.origin = toVector3(L, 2);
  ray.direction = toVector3(L, 3);
  if (ray.direction.norm() == 0.0) throw ArgumentError(L, 3, "the direction is zero");
  const OptionsTable options(L, 4, {"max_distance"});
  ray.tmax = options.number("max_distance", ray.tmax);
  const std::optional<RayHit> hit = rayScene(*handle).intersect(ray);
  if (!hit) {
    lua_pushnil(L);
    return 1;
  }
  lua_createtable(L, 0, 4);
  pushBody(L, handle, hit->body);
  lua_setfield(L, -2, "body");
  pushVector3(L, hit->point);
  lua_setfield(L, -2, "point");
  pushVector3(L, hit->normal);
  lua_setfield(L, -2, "normal");
  lua_pushnumber(L, hit->distance);
  lua_setfield(L, -2, "distance");
  return 1;
}

// world:remove_body(body): removes an obstacle or graspable body (a Body or its name). Body
// objects of later bodies follow; the removed one's Body objects fail when used.
int removeBody(lua_State* L) {
  const WorldHandle& handle = toWorldHandle(L, 1);
  const BodyRef ref = toBodyOf(L, 2, *handle);
  if (ref.kind != BodyRef::Kind::Body)
    throw ArgumentError(L, 2,
                        fmt::format("{} belongs to a robot: only obstacles and graspable bodies "
                                    "can be removed",
                                    bodyName(handle->world, ref)));
  handle->removeBody(ref.index);
  handle->rays.reset();  // indices moved: rebuilt on the next raycast
  return 0;
}

// The collision switch's target at `arg`: a Robot (all its links), else a body.
std::variant<int, BodyRef> collisionTarget(lua_State* L, int arg, const ScriptWorld& world) {
  if (const auto* robot = testObject<BoundRobot>(L, arg, kRobotClass)) {
    if (robot->world.get() != &world)
      throw ArgumentError(L, arg, "the robot belongs to another world (a clone?)");
    return robot->index;
  }
  return toBodyOf(L, arg, world);
}

// world:set_collision(a, [b,] enabled): a and b are bodies (or names) or robots. With one, every
// pair it is in; with two, that pair. Switches only turn pairs off: enabling undoes an earlier
// disabling, and never overrides a robot's own rules (links of one chain, for instance).
int setCollision(lua_State* L) {
  ScriptWorld& world = toWorld(L, 1);
  const bool pair = lua_gettop(L) >= 4;
  const bool enabled = toBoolean(L, pair ? 4 : 3);
  CollisionFilter& filter = world.world.collisionFilter();
  const auto a = collisionTarget(L, 2, world);
  if (!pair) {
    if (const int* robot = std::get_if<int>(&a))
      filter.setRobotEnabled(*robot, enabled);
    else
      filter.setBodyEnabled(std::get<BodyRef>(a), enabled);
    return 0;
  }
  if (std::holds_alternative<int>(a) || testObject<BoundRobot>(L, 3, kRobotClass) != nullptr)
    throw ArgumentError(L, 2, "a pair switch takes two bodies (links are bodies: robot:links())");
  filter.setPairEnabled(std::get<BodyRef>(a), toBodyOf(L, 3, world), enabled);
  return 0;
}

// world:collision_enabled(a [, b]): with one body or robot, whether its switch is on; with two
// bodies, whether collision detection looks at that pair at all (switches and robot rules).
int collisionEnabled(lua_State* L) {
  const ScriptWorld& world = toWorld(L, 1);
  const CollisionFilter& filter = world.world.collisionFilter();
  const auto a = collisionTarget(L, 2, world);
  if (isNone(L, 3)) {
    const int* robot = std::get_if<int>(&a);
    lua_pushboolean(L,
                    robot ? filter.robotEnabled(*robot) : filter.bodyEnabled(std::get<BodyRef>(a)));
    return 1;
  }
  if (std::holds_alternative<int>(a))
    throw ArgumentError(L, 2, "a pair takes two bodies (links are bodies: robot:links())");
  lua_pushboolean(L, filter.isActive(world.world, std::get<BodyRef>(a), toBodyOf(L, 3, world)));
  return 1;
}

int worldToString(lua_State* L) {
  const ScriptWorld& world = *toWorldHandle(L, 1);
  const std::string text =
      fmt::format("World({} bodies, {} robot{}{}{})", world.world.bodies().size(),
                  world.world.robotCount(), world.world.robotCount() == 1 ? "" : "s",
                  world.file.empty() ? "" : ", ", world.file.filename().string());
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

}  // namespace

void pushWorld(lua_State* L, WorldHandle world) {
  newObject<WorldHandle>(L, kWorldClass, std::move(world));
}

ScriptWorld& toWorld(lua_State* L, int arg) {
  return *toWorldHandle(L, arg);
}

void openWorldFunctions(lua_State* L) {
  const luaL_Reg methods[] = {
      {"add_obstacle", guarded<addObstacle>},
      {"add_object", guarded<addObject>},
      {"add_robot", guarded<addRobot>},
      {"save", guarded<save>},
      {"clone", guarded<clone>},
      {"render", guarded<render>},
      {"step", guarded<stepWorld>},
      {"simulate", guarded<simulateWorld>},
      {"validate", guarded<validateWorld>},
      {"set_gravity", guarded<setGravity>},
      {"gravity", guarded<gravity>},
      {"time", guarded<worldTime>},
      {"file", guarded<file>},
      {"bodies", guarded<bodies>},
      {"body", guarded<body>},
      {"robots", guarded<robots>},
      {"robot", guarded<robot>},
      {"contacts", guarded<contacts>},
      {"collides", guarded<collides>},
      {"collisions", guarded<collisions>},
      {"distance", guarded<distance>},
      {"raycast", guarded<raycast>},
      {"remove_body", guarded<removeBody>},
      {"set_collision", guarded<setCollision>},
      {"collision_enabled", guarded<collisionEnabled>},
      {nullptr, nullptr},
  };
  defineClass(L, kWorldClass, methods, destroyObject<WorldHandle>, guarded<worldToString>);
  const luaL_Reg functions[] = {
      {"load_world", guarded<loadWorld>},
      {"new_world", guarded<newWorld>},
      {nullptr, nullptr},
  };
  luaL_setfuncs(L, functions, 0);
}

}  // namespace graspkit::lua
