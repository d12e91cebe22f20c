// The Grasp class: a hand's contacts with one object and the qualities of its wrench space.

#include <fmt/format.h>

#include <cmath>

#include "bound_objects.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/plugin/registry.hpp"
#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {
namespace {

int epsilon(lua_State* L) {
  lua_pushnumber(L, toGrasp(L, 1).grasp.epsilon);
  return 1;
}

int volume(lua_State* L) {
  lua_pushnumber(L, toGrasp(L, 1).grasp.volume);
  return 1;
}

int forceClosure(lua_State* L) {
  lua_pushboolean(L, toGrasp(L, 1).grasp.forceClosure);
  return 1;
}

// grasp:quality(name): any registered quality measure ("epsilon", "volume", a plugin's).
int quality(lua_State* L) {
  const BoundGrasp& grasp = toGrasp(L, 1);
  const std::string name = toString(L, 2);
  lua_pushnumber(L, makeQualityMeasure(name)->evaluate(grasp.grasp.wrenchSpace));
  return 1;
}

int contacts(lua_State* L) {
  const BoundGrasp& grasp = toGrasp(L, 1);
  checkGraspBodies(grasp);
  const auto& found = grasp.grasp.contacts;
  lua_createtable(L, static_cast<int>(found.size()), 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    pushContact(L, grasp.world, found[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int contactCount(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(toGrasp(L, 1).grasp.contacts.size()));
  return 1;
}

int object(lua_State* L) {
  const BoundGrasp& grasp = toGrasp(L, 1);
  checkGraspBodies(grasp);
  pushBody(L, grasp.world, grasp.grasp.object);
  return 1;
}

int robot(lua_State* L) {
  const BoundGrasp& grasp = toGrasp(L, 1);
  pushRobot(L, grasp.world, grasp.grasp.robot);
  return 1;
}

// Why the wrench space could not be built (no contacts, a flat wrench set, ...), or nil.
int failure(lua_State* L) {
  const GraspWrenchSpace& gws = toGrasp(L, 1).grasp.wrenchSpace;
  if (gws.built) {
    lua_pushnil(L);
  } else {
    lua_pushstring(L, gws.failure.c_str());
  }
  return 1;
}

int graspToString(lua_State* L) {
  const BoundGrasp& bound = toGrasp(L, 1);
  const Grasp& grasp = bound.grasp;
  const std::string text =
      fmt::format("Grasp({} on {}, {} contacts, epsilon {:.6g}, volume {:.6g}{})",
                  bound.world->world.robot(grasp.robot).name(),
                  bodyName(bound.world->world, grasp.object), grasp.contacts.size(), grasp.epsilon,
                  grasp.volume, grasp.forceClosure ? ", force closure" : "");
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

}  // namespace

void pushGrasp(lua_State* L, const WorldHandle& world, Grasp grasp) {
  newObject<BoundGrasp>(L, kGraspClass,
                        BoundGrasp{world, std::move(grasp), world->removedBodies.size()});
}

void checkGraspBodies(const BoundGrasp& grasp) {
  if (grasp.removalsSeen != grasp.world->removedBodies.size())
    throw Error(
        "bodies were removed from the world since this grasp was measured; measure it again");
}

BoundGrasp& toGrasp(lua_State* L, int arg) {
  return toObject<BoundGrasp>(L, arg, kGraspClass, "Grasp");
}

void registerGraspClass(lua_State* L) {
  const luaL_Reg methods[] = {
      {"epsilon", guarded<epsilon>},
      {"volume", guarded<volume>},
      {"force_closure", guarded<forceClosure>},
      {"quality", guarded<quality>},
      {"contacts", guarded<contacts>},
      {"contact_count", guarded<contactCount>},
      {"object", guarded<object>},
      {"robot", guarded<robot>},
      {"failure", guarded<failure>},
      {nullptr, nullptr},
  };
  defineClass(L, kGraspClass, methods, destroyObject<BoundGrasp>, guarded<graspToString>);
}

}  // namespace graspkit::lua
