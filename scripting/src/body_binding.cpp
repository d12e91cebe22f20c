// The Body class: a free body (obstacle or graspable object), a robot link or base, or a mount
// piece, as the engine's BodyRef names them; and contacts as plain tables.

#include <fmt/format.h>

#include "bound_objects.hpp"
#include "graspkit/error.hpp"
#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {
namespace {

const char* kindName(const World& world, const BodyRef& ref) {
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return world.bodies()[ref.index].isDynamic() ? "object" : "obstacle";
    case BodyRef::Kind::Link:
      return "link";
    case BodyRef::Kind::Mount:
      return "mount";
  }
  return "?";
}

int name(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushstring(L, bodyName(body.world->world, body.ref).c_str());
  return 1;
}

int kind(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushstring(L, kindName(body.world->world, body.ref));
  return 1;
}

int pose(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  pushPose(L, bodyPose(body.world->world, body.ref));
  return 1;
}

int setPose(lua_State* L) {
  BoundBody& body = toBody(L, 1);
  const Transform pose = toPose(L, 2);
  if (body.ref.kind != BodyRef::Kind::Body) {
    throw Error(fmt::format("{} is a {}: move its robot instead",
                            bodyName(body.world->world, body.ref),
                            kindName(body.world->world, body.ref)));
  }
  body.world->world.bodies()[body.ref.index].setPose(pose);
  return 0;
}

int file(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushstring(L, bodyModel(body.world->world, body.ref).file.c_str());
  return 1;
}

int material(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const std::string_view text = materialName(bodyModel(body.world->world, body.ref).material);
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int mass(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushnumber(L, bodyModel(body.world->world, body.ref).mass);
  return 1;
}

int cog(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  pushVector3(L, bodyModel(body.world->world, body.ref).cog);
  return 1;
}

// The inertia tensor per unit mass about the CoG in body axes (mm^2), as rows.
int inertia(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const Matrix3& inertia = bodyModel(body.world->world, body.ref).inertia;
  lua_createtable(L, 3, 0);
  for (int r = 0; r < 3; ++r) {
    pushVector3(L, inertia.row(r).transpose());
    lua_rawseti(L, -2, r + 1);
  }
  return 1;
}

int triangleCount(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const auto& mesh = bodyModel(body.world->world, body.ref).mesh;
  lua_pushinteger(L, mesh ? static_cast<lua_Integer>(mesh->triangles.size()) : 0);
  return 1;
}

int isDynamic(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushboolean(L, body.ref.kind == BodyRef::Kind::Body &&
                         body.world->world.bodies()[body.ref.index].isDynamic());
  return 1;
}

int world(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  pushWorld(L, body.world);
  return 1;
}

int bodyToString(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const std::string text = fmt::format("Body({}, {})", bodyName(body.world->world, body.ref),
                                       kindName(body.world->world, body.ref));
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int bodyEquals(lua_State* L) {
  const auto* a = testObject<BoundBody>(L, 1, kBodyClass);
  const auto* b = testObject<BoundBody>(L, 2, kBodyClass);
  lua_pushboolean(L, a != nullptr && b != nullptr && a->world == b->world && a->ref == b->ref);
  return 1;
}

}  // namespace

void pushBody(lua_State* L, const WorldHandle& world, const BodyRef& ref) {
  newObject<BoundBody>(L, kBodyClass, BoundBody{world, ref});
}

BoundBody& toBody(lua_State* L, int arg) {
  return toObject<BoundBody>(L, arg, kBodyClass, "Body");
}

BodyRef toBodyOf(lua_State* L, int arg, const ScriptWorld& world) {
  if (lua_type(L, arg) == LUA_TSTRING) {
    const std::string wanted = toString(L, arg);
    const std::vector<BodyRef> all = worldBodies(world.world);
    for (const BodyRef& ref : all) {
      if (bodyName(world.world, ref) == wanted) return ref;
    }
    std::string known;
    for (const Body& body : world.world.bodies()) known += (known.empty() ? "" : ", ") + body.name;
    throw ArgumentError(L, arg,
                        fmt::format("no body or link '{}' in the world (bodies: {}; links are "
                                    "named <robot>_palm and <robot>_chain<c>_link<l>, from 0)",
                                    wanted, known.empty() ? "none" : known));
  }
  const BoundBody& body = toObject<BoundBody>(L, arg, kBodyClass, "Body or body name");
  if (body.world.get() != &world) {
    throw ArgumentError(L, arg, "the body belongs to another world (a clone?)");
  }
  return body.ref;
}

void pushContact(lua_State* L, const WorldHandle& world, const Contact& contact) {
  lua_createtable(L, 0, 9);
  pushBody(L, world, contact.body1);
  lua_setfield(L, -2, "body1");
  pushBody(L, world, contact.body2);
  lua_setfield(L, -2, "body2");
  pushVector3(L, contact.position1);
  lua_setfield(L, -2, "point1");
  pushVector3(L, contact.position2);
  lua_setfield(L, -2, "point2");
  pushVector3(L, contact.normal);
  lua_setfield(L, -2, "normal");
  lua_pushnumber(L, contact.distance);
  lua_setfield(L, -2, "distance");
  lua_pushnumber(L, contact.mu);
  lua_setfield(L, -2, "mu");
  lua_pushstring(L, contactModelName(contact.model));
  lua_setfield(L, -2, "model");
  lua_pushnumber(L, contact.torsion);
  lua_setfield(L, -2, "torsion");
}

void registerBodyClass(lua_State* L) {
  const luaL_Reg methods[] = {
      {"name", guarded<name>},
      {"kind", guarded<kind>},
      {"pose", guarded<pose>},
      {"set_pose", guarded<setPose>},
      {"file", guarded<file>},
      {"material", guarded<material>},
      {"mass", guarded<mass>},
      {"cog", guarded<cog>},
      {"inertia", guarded<inertia>},
      {"triangle_count", guarded<triangleCount>},
      {"is_dynamic", guarded<isDynamic>},
      {"world", guarded<world>},
      {nullptr, nullptr},
  };
  defineClass(L, kBodyClass, methods, destroyObject<BoundBody>, guarded<bodyToString>, bodyEquals);
}

}  // namespace graspkit::lua
