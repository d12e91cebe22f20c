// The Body class: a free body (obstacle or graspable object), a robot link or base, or a mount
// piece, as the engine's BodyRef names them; and contacts as plain tables.

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "bound_objects.hpp"
#include "graspkit/base/error.hpp"
#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {
namespace {

const char* kindName(const World& world, const BodyRef& ref) {
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return nameOf(world.bodies()[ref.index].kind).data();  // "graspable" or "obstacle"
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

// body:velocity() -> v, w: the centre of mass's velocity (mm/s) and the angular velocity (rad/s),
// world frame. Zero for bodies that do not move by themselves (obstacles, links).
int velocity(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  Vector6 v = Vector6::Zero();
  if (body.ref.kind == BodyRef::Kind::Body) v = body.world->world.bodies()[body.ref.index].state.v;
  pushVector3(L, v.head<3>());
  pushVector3(L, v.tail<3>());
  return 2;
}

// body:set_velocity(v [, w]): graspable bodies only.
int setVelocity(lua_State* L) {
  BoundBody& body = toBody(L, 1);
  const Vector3 linear = toVector3(L, 2);
  const Vector3 angular = isNone(L, 3) ? Vector3::Zero() : toVector3(L, 3);
  if (body.ref.kind != BodyRef::Kind::Body ||
      !body.world->world.bodies()[body.ref.index].isDynamic()) {
    throw Error(fmt::format("{} is not a graspable body: only those move by dynamics",
                            bodyName(body.world->world, body.ref)));
  }
  body.world->world.bodies()[body.ref.index].state.v << linear, angular;
  return 0;
}

int file(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  lua_pushstring(L, bodyModel(body.world->world, body.ref).file.c_str());
  return 1;
}

int material(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const std::string_view text = nameOf(bodyModel(body.world->world, body.ref).material);
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

// The mesh's vertices in the world frame (default) or the body's own: {frame = "world" | "body"}.
std::vector<Vector3> vertices(lua_State* L, const BoundBody& body, int options_arg) {
  const OptionsTable options(L, options_arg, {"frame"});
  const std::string frame = options.string("frame", "world");
  if (frame != "world" && frame != "body")
    throw ArgumentError(L, options_arg, "option 'frame' must be 'world' or 'body'");
  const auto& mesh = bodyModel(body.world->world, body.ref).mesh;
  std::vector<Vector3> points = mesh ? mesh->vertices : std::vector<Vector3>{};
  if (frame == "world") {
    const Transform pose = bodyPose(body.world->world, body.ref);
    for (Vector3& p : points) p = pose * p;
  }
  return points;
}

// body:vertices([{frame = "world"}]) -> {{x, y, z}, ...}, mm.
int vertexList(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const std::vector<Vector3> points = vertices(L, body, 2);
  lua_createtable(L, static_cast<int>(points.size()), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    pushVector3(L, points[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

// body:bounds([{frame = "world"}]) -> {min = {x, y, z}, max = {x, y, z}}: the axis-aligned box
// of the mesh's vertices in that frame; nil for a body without geometry.
int bounds(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const std::vector<Vector3> points = vertices(L, body, 2);
  if (points.empty()) {
    lua_pushnil(L);
    return 1;
  }
  Vector3 low = points.front(), high = points.front();
  for (const Vector3& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  lua_createtable(L, 0, 2);
  pushVector3(L, low);
  lua_setfield(L, -2, "min");
  pushVector3(L, high);
  lua_setfield(L, -2, "max");
  return 1;
}

// body:max_radius(): the largest distance from the body's origin to a vertex of its mesh (mm;
// 0 without geometry), the radius of the smallest sphere about the origin holding the body.
int maxRadius(lua_State* L) {
  const BoundBody& body = toBody(L, 1);
  const auto& mesh = bodyModel(body.world->world, body.ref).mesh;
  double radius = 0.0;
  if (mesh)
    for (const Vector3& p : mesh->vertices) radius = std::max(radius, p.norm());
  lua_pushnumber(L, radius);
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
  auto* a = testObject<BoundBody>(L, 1, kBodyClass);
  auto* b = testObject<BoundBody>(L, 2, kBodyClass);
  lua_pushboolean(L, a != nullptr && b != nullptr && followRemovals(*a) && followRemovals(*b) &&
                         a->world == b->world && a->ref == b->ref);
  return 1;
}

}  // namespace

void pushBody(lua_State* L, const WorldHandle& world, const BodyRef& ref) {
  newObject<BoundBody>(L, kBodyClass, BoundBody{world, ref, world->removedBodies.size()});
}

bool followRemovals(BoundBody& body) {
  if (body.ref.kind != BodyRef::Kind::Body) {
    body.removalsSeen = body.world->removedBodies.size();
    return true;
  }
  return body.world->followRemovals(body.ref.index, body.removalsSeen);
}

BoundBody& toBody(lua_State* L, int arg) {
  BoundBody& body = toObject<BoundBody>(L, arg, kBodyClass, "Body");
  if (!followRemovals(body)) throw ArgumentError(L, arg, "the body was removed from its world");
  return body;
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
  BoundBody& body = toObject<BoundBody>(L, arg, kBodyClass, "Body or body name");
  if (!followRemovals(body)) throw ArgumentError(L, arg, "the body was removed from its world");
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
  lua_pushlstring(L, nameOf(contact.model).data(), nameOf(contact.model).size());
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
      {"velocity", guarded<velocity>},
      {"set_velocity", guarded<setVelocity>},
      {"file", guarded<file>},
      {"material", guarded<material>},
      {"mass", guarded<mass>},
      {"cog", guarded<cog>},
      {"inertia", guarded<inertia>},
      {"triangle_count", guarded<triangleCount>},
      {"is_dynamic", guarded<isDynamic>},
      {"vertices", guarded<vertexList>},
      {"bounds", guarded<bounds>},
      {"max_radius", guarded<maxRadius>},
      {"world", guarded<world>},
      {nullptr, nullptr},
  };
  defineClass(L, kBodyClass, methods, destroyObject<BoundBody>, guarded<bodyToString>, bodyEquals);
}

}  // namespace graspkit::lua
