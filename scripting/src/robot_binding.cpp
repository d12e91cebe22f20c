// The Robot class: DOFs, poses, links, inverse kinematics, and the hand motions (autograsp,
// open, approach) and grasp analysis for robots that are hands.

#include <fmt/format.h>

#include "bound_objects.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/planning/eigengrasp_map.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {
namespace {

const Robot& robotOf(const BoundRobot& bound) {
  return bound.world->world.robot(bound.index);
}

int name(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  lua_pushstring(L, robotOf(robot).name().c_str());
  return 1;
}

int type(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  lua_pushstring(L, robotOf(robot).model().type.c_str());
  return 1;
}

int typeProvider(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  lua_pushstring(L, robotOf(robot).model().typeProvider.c_str());
  return 1;
}

int index(lua_State* L) {
  lua_pushinteger(L, toRobot(L, 1).index + 1);
  return 1;
}

int isHand(lua_State* L) {
  lua_pushboolean(L, robotOf(toRobot(L, 1)).model().isHand);
  return 1;
}

int dofCount(lua_State* L) {
  lua_pushinteger(L, robotOf(toRobot(L, 1)).dofCount());
  return 1;
}

int dofs(lua_State* L) {
  pushNumberList(L, robotOf(toRobot(L, 1)).dofValues());
  return 1;
}

// robot:set_dofs(values [, {limits = "clamp" | "ignore" | "error"}])
int setDofs(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  const std::vector<double> values = toNumberList(L, 2);
  const OptionsTable options(L, 3, {"limits"});
  const std::string limits = options.string("limits", "clamp");
  const Robot& current = robotOf(robot);
  if (static_cast<int>(values.size()) != current.dofCount()) {
    throw ArgumentError(
        L, 2,
        fmt::format("{} DOF values expected ({} has {}), got {}", current.dofCount(),
                    current.name(), current.dofCount(), values.size()));
  }
  LimitPolicy policy = LimitPolicy::Clamp;
  if (limits == "ignore") {
    policy = LimitPolicy::Ignore;
  } else if (limits == "error") {
    const auto& model_dofs = current.model().dofs;
    for (std::size_t d = 0; d < values.size(); ++d) {
      if (values[d] < model_dofs[d].min || values[d] > model_dofs[d].max) {
        throw ArgumentError(L, 2,
                            fmt::format("DOF {} value {} outside [{}, {}]", d + 1, values[d],
                                        model_dofs[d].min, model_dofs[d].max));
      }
    }
  } else if (limits != "clamp") {
    throw ArgumentError(L, 3, "limits must be 'clamp', 'ignore' or 'error'");
  }
  robot.world->world.setDofValues(robot.index, values, policy);
  return 0;
}

// {{min = ..., max = ...}, ...}: radians, mm for prismatic DOFs.
int dofLimits(lua_State* L) {
  const auto& model_dofs = robotOf(toRobot(L, 1)).model().dofs;
  lua_createtable(L, static_cast<int>(model_dofs.size()), 0);
  for (std::size_t d = 0; d < model_dofs.size(); ++d) {
    lua_createtable(L, 0, 2);
    lua_pushnumber(L, model_dofs[d].min);
    lua_setfield(L, -2, "min");
    lua_pushnumber(L, model_dofs[d].max);
    lua_setfield(L, -2, "max");
    lua_rawseti(L, -2, static_cast<lua_Integer>(d + 1));
  }
  return 1;
}

int robotPose(lua_State* L) {
  pushPose(L, robotOf(toRobot(L, 1)).pose());
  return 1;
}

int setPose(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  robot.world->world.setRobotPose(robot.index, toPose(L, 2));
  return 0;
}

int chainCount(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(robotOf(toRobot(L, 1)).model().chains.size()));
  return 1;
}

// {{chain 1's link poses}, {chain 2's}, ...}: world poses, 1-based.
int linkPoses(lua_State* L) {
  const auto& poses = robotOf(toRobot(L, 1)).linkPoses();
  lua_createtable(L, static_cast<int>(poses.size()), 0);
  for (std::size_t c = 0; c < poses.size(); ++c) {
    lua_createtable(L, static_cast<int>(poses[c].size()), 0);
    for (std::size_t l = 0; l < poses[c].size(); ++l) {
      pushPose(L, poses[c][l]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(l + 1));
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(c + 1));
  }
  return 1;
}

int base(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  pushBody(L, robot.world, BodyRef::robotBase(robot.index));
  return 1;
}

// robot:link(chain, link): 1-based.
int link(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const int chain = toInteger(L, 2);
  const int link_index = toInteger(L, 3);
  const auto& chains = robotOf(robot).model().chains;
  if (chain < 1 || chain > static_cast<int>(chains.size())) {
    throw ArgumentError(
        L, 2, fmt::format("chain {} out of range (the robot has {})", chain, chains.size()));
  }
  const int links = static_cast<int>(chains[chain - 1].links.size());
  if (link_index < 1 || link_index > links) {
    throw ArgumentError(
        L, 3, fmt::format("link {} out of range (chain {} has {})", link_index, chain, links));
  }
  pushBody(L, robot.world, BodyRef::robotLink(robot.index, LinkRef{chain - 1, link_index - 1}));
  return 1;
}

// The base, then every link chain by chain.
int links(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const auto& chains = robotOf(robot).model().chains;
  lua_newtable(L);
  lua_Integer n = 0;
  pushBody(L, robot.world, BodyRef::robotBase(robot.index));
  lua_rawseti(L, -2, ++n);
  for (int c = 0; c < static_cast<int>(chains.size()); ++c) {
    for (int l = 0; l < static_cast<int>(chains[c].links.size()); ++l) {
      pushBody(L, robot.world, BodyRef::robotLink(robot.index, LinkRef{c, l}));
      lua_rawseti(L, -2, ++n);
    }
  }
  return 1;
}

// robot:inverse_kinematics(pose [, {chain = 1}]) -> DOF values, or nil and the reason. The pose
// is where the end of the chain (its last link's frame) should be, in the world.
int inverseKinematics(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const Transform target = toPose(L, 2);
  const OptionsTable options(L, 3, {"chain", "max_iterations"});
  IkRequest request;
  request.chain = options.integer("chain", 1) - 1;
  request.maxIterations = options.integer("max_iterations", request.maxIterations);
  const int chains = static_cast<int>(robotOf(robot).model().chains.size());
  if (request.chain < 0 || request.chain >= chains) {
    throw ArgumentError(
        L, 3, fmt::format("chain {} out of range (the robot has {})", request.chain + 1, chains));
  }
  const IkResult result = graspkit::inverseKinematics(robotOf(robot), target, request);
  if (!result.success) {
    lua_pushnil(L);
    lua_pushstring(L, result.failure.c_str());
    return 2;
  }
  pushNumberList(L, result.dofValues);
  return 1;
}

void pushContacts(lua_State* L, const WorldHandle& world, const std::vector<Contact>& contacts) {
  lua_createtable(L, static_cast<int>(contacts.size()), 0);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    pushContact(L, world, contacts[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

// {dofs = {...}, contacts = {...}, steps = n, ended = "settled" | ...}
void pushMotion(lua_State* L, const WorldHandle& world, const AutoGraspResult& result) {
  lua_createtable(L, 0, 4);
  pushNumberList(L, result.dofValues);
  lua_setfield(L, -2, "dofs");
  pushContacts(L, world, result.contacts);
  lua_setfield(L, -2, "contacts");
  lua_pushinteger(L, result.iterations);
  lua_setfield(L, -2, "steps");
  lua_pushlstring(L, nameOf(result.end).data(), nameOf(result.end).size());
  lua_setfield(L, -2, "ended");
}

// hand:autograsp{dynamic = true, seconds = 2}: the hand's DOF controllers drive every DOF
// towards the limit it closes to, and the world is simulated until the DOFs have stopped (all
// slower than 1e-3 for 0.1 s) or `seconds` have passed. Returns {time, steps, settled}.
int dynamicAutograsp(lua_State* L, BoundRobot& robot, double seconds) {
  World& world = robot.world->world;
  setClosingTargets(world, robot.index);
  int still_steps = 0, steps = 0;
  const int needed = static_cast<int>(std::ceil(0.1 / kDefaultTimeStep));
  SimulateRequest request{.seconds = seconds};
  request.onStep = [&](const World& w, const StepReport&) {
    ++steps;
    double fastest = 0.0;
    for (double v : w.robot(robot.index).dofVelocities()) fastest = std::max(fastest, std::abs(v));
    still_steps = fastest < 1e-3 ? still_steps + 1 : 0;
    return still_steps < needed;
  };
  const SimulateResult result = simulate(world, request);
  lua_createtable(L, 0, 3);
  lua_pushnumber(L, result.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, steps);
  lua_setfield(L, -2, "steps");
  lua_pushboolean(L, result.stoppedEarly);
  lua_setfield(L, -2, "settled");
  return 1;
}

// robot:set_dof_targets{...}: the DOF controllers' set-points (rad or mm) for dynamics.
int setDofTargets(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  robot.world->world.setDofTargets(robot.index, toNumberList(L, 2));
  return 0;
}

int dofTargets(lua_State* L) {
  pushNumberList(L, robotOf(toRobot(L, 1)).dofTargets());
  return 1;
}

int dofVelocities(lua_State* L) {
  pushNumberList(L, robotOf(toRobot(L, 1)).dofVelocities());
  return 1;
}

// hand:autograsp([{speed = 1, stop_at_contact = false, max_steps = 500}]), GraspIt!'s static
// autograsp; with dynamic = true, the dynamic one above.
int autograsp(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  const OptionsTable options(L, 2, {"speed", "stop_at_contact", "max_steps", "dynamic", "seconds"});
  if (options.boolean("dynamic", false)) {
    return dynamicAutograsp(L, robot, options.number("seconds", 2.0));
  }
  AutoGraspOptions request;
  request.speedFactor = options.number("speed", request.speedFactor);
  request.stopAtContact = options.boolean("stop_at_contact", request.stopAtContact);
  request.maxIterations = options.integer("max_steps", request.maxIterations);
  const AutoGraspResult result = autoGrasp(robot.world->world, robot.index, request);
  pushMotion(L, robot.world, result);
  return 1;
}

// hand:open() -> whether the hand ends free of collisions.
int open(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  lua_pushboolean(L, openUntilFree(robot.world->world, robot.index));
  return 1;
}

// hand:approach_to_contact([{max_distance = 500, step = 10}]) -> whether it touched, and the
// motion's record.
int approachToContact(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  const OptionsTable options(L, 2, {"max_distance", "step", "direction"});
  ApproachOptions request;
  request.maxDistance = options.number("max_distance", request.maxDistance);
  request.step = options.number("step", request.step);
  request.direction = options.vector3("direction");
  if (request.maxDistance < 0 || request.step <= 0) {
    throw ArgumentError(L, 2, "max_distance must be >= 0 and step > 0");
  }
  if (request.direction && request.direction->norm() < 1e-12)
    throw ArgumentError(L, 2, "option 'direction' is zero");
  const AutoGraspResult result =
      graspkit::approachToContact(robot.world->world, robot.index, request);
  lua_pushboolean(L, result.end == MotionEnd::Contact);
  pushMotion(L, robot.world, result);
  return 2;
}

// hand:move_dofs_to_contacts(targets, steps [, {stop_at_contact = false, max_steps = 500}]):
// GraspIt!'s moveDOFToContacts. Each DOF moves toward its target by |step| per step until its
// links touch something; returns the motion's record.
int moveDofsToContacts(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  DofMotion motion;
  motion.targets = toNumberList(L, 2);
  motion.steps = toNumberList(L, 3);
  const OptionsTable options(L, 4, {"stop_at_contact", "max_steps"});
  motion.stopAtContact = options.boolean("stop_at_contact", motion.stopAtContact);
  motion.maxIterations = options.integer("max_steps", motion.maxIterations);
  const int dofs = robotOf(robot).dofCount();
  for (int arg : {2, 3}) {
    const std::size_t n = (arg == 2 ? motion.targets : motion.steps).size();
    if (static_cast<int>(n) != dofs)
      throw ArgumentError(L, arg, fmt::format("{} values expected (one per DOF), got {}", dofs, n));
  }
  if (motion.maxIterations < 1) throw ArgumentError(L, 4, "option 'max_steps' must be >= 1");
  const AutoGraspResult result =
      graspkit::moveDofsToContacts(robot.world->world, robot.index, motion);
  pushMotion(L, robot.world, result);
  return 1;
}

// The hand's eigengrasp map; an error naming the robot when it has no eigengrasps.
EigengraspMap eigengraspMap(const BoundRobot& robot) {
  return EigengraspMap(robotOf(robot).model());
}

// robot:eigengrasps() -> {grasps = {{direction = {...}, min = a, max = b}, ...}, origin = {...},
// norm = {...}, identity = bool}: dofs = origin + norm .* (sum of a_i direction_i).
int eigengrasps(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const EigengraspMap map = eigengraspMap(robot);
  lua_createtable(L, 0, 4);
  lua_createtable(L, map.size(), 0);
  for (int i = 0; i < map.size(); ++i) {
    lua_createtable(L, 0, 3);
    const Eigen::VectorXd direction = map.direction(i);
    pushNumberList(L, {direction.data(), static_cast<std::size_t>(direction.size())});
    lua_setfield(L, -2, "direction");
    lua_pushnumber(L, map.minAmplitude(i));
    lua_setfield(L, -2, "min");
    lua_pushnumber(L, map.maxAmplitude(i));
    lua_setfield(L, -2, "max");
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "grasps");
  pushNumberList(L, {map.origin().data(), static_cast<std::size_t>(map.origin().size())});
  lua_setfield(L, -2, "origin");
  pushNumberList(L, {map.norm().data(), static_cast<std::size_t>(map.norm().size())});
  lua_setfield(L, -2, "norm");
  lua_pushboolean(L, robotOf(robot).model().eigengrasps.identity);
  lua_setfield(L, -2, "identity");
  return 1;
}

// robot:eigengrasp_amplitudes(): the amplitudes nearest (least squares) to the current DOFs.
int eigengraspAmplitudes(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const auto& values = robotOf(robot).dofValues();
  const Eigen::VectorXd a = eigengraspMap(robot).amplitudes(
      Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())));
  pushNumberList(L, {a.data(), static_cast<std::size_t>(a.size())});
  return 1;
}

// robot:set_eigengrasp_amplitudes(a): DOFs from amplitudes, each clamped into its range.
int setEigengraspAmplitudes(lua_State* L) {
  BoundRobot& robot = toRobot(L, 1);
  const std::vector<double> a = toNumberList(L, 2);
  const EigengraspMap map = eigengraspMap(robot);
  if (static_cast<int>(a.size()) != map.size())
    throw ArgumentError(L, 2,
                        fmt::format("{} amplitudes expected (the robot has {} eigengrasps), got {}",
                                    map.size(), map.size(), a.size()));
  const Eigen::VectorXd dofs =
      map.dofs(Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size())));
  robot.world->world.setDofValues(robot.index, std::span<const double>(dofs.data(), dofs.size()));
  return 0;
}

// robot:virtual_contacts() -> {{link = Body, point = {...}, normal = {...}}, ...} in the world
// frame, and whether they were derived from the geometry (the robot file names none).
int virtualContacts(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const Robot& r = robotOf(robot);
  const bool derived = r.model().virtualContacts.empty();
  const std::vector<VirtualContact> contacts =
      derived ? deriveVirtualContacts(r) : r.model().virtualContacts;
  lua_createtable(L, static_cast<int>(contacts.size()), 0);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const VirtualContact& contact = contacts[i];
    const PlacedVirtualContact placed = placeVirtualContact(r, contact);
    lua_createtable(L, 0, 3);
    pushBody(L, robot.world,
             contact.finger < 0
                 ? BodyRef::robotBase(robot.index)
                 : BodyRef::robotLink(robot.index, LinkRef{contact.finger, contact.link}));
    lua_setfield(L, -2, "link");
    pushVector3(L, placed.point);
    lua_setfield(L, -2, "point");
    pushVector3(L, placed.normal);
    lua_setfield(L, -2, "normal");
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_pushboolean(L, derived);
  return 2;
}

// hand:energy(object [, name = "contact"]): the search energy a planner would give the hand where
// it stands (lower is better); nil and "collides" when the energy rejects a colliding hand.
int energy(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  PlanningRequest request;
  request.object = toBodyOf(L, 2, *robot.world);
  request.energy = isNone(L, 3) ? host::PlanSettings{}.energy : toString(L, 3);
  request.world = std::make_shared<const World>(robot.world->world.clone());
  request.robot = robot.index;
  request.position = PositionSpace::Complete;
  request.posture = PostureSpace::Dof;
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  std::unique_ptr<SearchEnergy> searchEnergy = makeSearchEnergy(request);
  if (searchEnergy->rejectsCollisions() && scene->handCollides()) {
    lua_pushnil(L);
    lua_pushstring(L, "collides");
    return 2;
  }
  lua_pushnumber(L, searchEnergy->evaluate(*scene));
  return 1;
}

// hand:contacts([object]): the hand's contacts, seen from its links.
int contacts(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  std::optional<BodyRef> object;
  if (!isNone(L, 2)) object = toBodyOf(L, 2, *robot.world);
  const std::vector<Contact> found =
      robotContacts(robot.world->world, robot.index, object ? &*object : nullptr);
  pushContacts(L, robot.world, found);
  return 1;
}

WrenchSpaceType wrenchSpaceType(lua_State* L, int arg, const std::string& name) {
  if (const auto type = valueNamed<WrenchSpaceType>(name)) return *type;
  throw ArgumentError(L, arg, fmt::format("gws '{}' is not 'L1' or 'Linf'", name));
}

// hand:grasp(object [, {gws = "L1" | "Linf"}]) -> Grasp of the hand's current contacts.
int grasp(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  // hand:grasp([object] [, options]): the world's first graspable body when none is given.
  const bool named = !isNone(L, 2) && lua_type(L, 2) != LUA_TTABLE;
  const BodyRef object =
      named ? toBodyOf(L, 2, *robot.world) : host::defaultObject(robot.world->world);
  const int optionsArg = named ? 3 : 2;
  const OptionsTable options(L, optionsArg, {"gws"});
  GraspRequest request;
  request.wrenchSpace.type = wrenchSpaceType(
      L, optionsArg, options.string("gws", std::string(nameOf(request.wrenchSpace.type))));
  Grasp result = analyzeGrasp(robot.world->world, robot.index, object, request);
  pushGrasp(L, robot.world, std::move(result));
  return 1;
}

int world(lua_State* L) {
  pushWorld(L, toRobot(L, 1).world);
  return 1;
}

int robotToString(lua_State* L) {
  const BoundRobot& robot = toRobot(L, 1);
  const Robot& r = robotOf(robot);
  const std::string text = fmt::format("Robot({} #{}, {}, {} DOFs)", r.name(), robot.index + 1,
                                       r.model().type, r.dofCount());
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int robotEquals(lua_State* L) {
  const auto* a = testObject<BoundRobot>(L, 1, kRobotClass);
  const auto* b = testObject<BoundRobot>(L, 2, kRobotClass);
  lua_pushboolean(L, a != nullptr && b != nullptr && a->world == b->world && a->index == b->index);
  return 1;
}

}  // namespace

void pushRobot(lua_State* L, const WorldHandle& world, int index) {
  newObject<BoundRobot>(L, kRobotClass, BoundRobot{world, index});
}

BoundRobot& toRobot(lua_State* L, int arg) {
  return toObject<BoundRobot>(L, arg, kRobotClass, "Robot");
}

void registerRobotClass(lua_State* L) {
  const luaL_Reg methods[] = {
      {"name", guarded<name>},
      {"type", guarded<type>},
      {"type_provider", guarded<typeProvider>},
      {"index", guarded<index>},
      {"is_hand", guarded<isHand>},
      {"dof_count", guarded<dofCount>},
      {"dofs", guarded<dofs>},
      {"set_dofs", guarded<setDofs>},
      {"dof_limits", guarded<dofLimits>},
      {"pose", guarded<robotPose>},
      {"set_pose", guarded<setPose>},
      {"chain_count", guarded<chainCount>},
      {"link_poses", guarded<linkPoses>},
      {"base", guarded<base>},
      {"link", guarded<link>},
      {"links", guarded<links>},
      {"inverse_kinematics", guarded<inverseKinematics>},
      {"autograsp", guarded<autograsp>},
      {"set_dof_targets", guarded<setDofTargets>},
      {"dof_targets", guarded<dofTargets>},
      {"dof_velocities", guarded<dofVelocities>},
      {"open", guarded<open>},
      {"approach_to_contact", guarded<approachToContact>},
      {"move_dofs_to_contacts", guarded<moveDofsToContacts>},
      {"eigengrasps", guarded<eigengrasps>},
      {"eigengrasp_amplitudes", guarded<eigengraspAmplitudes>},
      {"set_eigengrasp_amplitudes", guarded<setEigengraspAmplitudes>},
      {"virtual_contacts", guarded<virtualContacts>},
      {"energy", guarded<energy>},
      {"contacts", guarded<contacts>},
      {"grasp", guarded<grasp>},
      {"world", guarded<world>},
      {nullptr, nullptr},
  };
  defineClass(L, kRobotClass, methods, destroyObject<BoundRobot>, guarded<robotToString>,
              robotEquals);
}

}  // namespace graspkit::lua
