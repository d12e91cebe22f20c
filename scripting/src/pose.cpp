// Poses in Lua: plain tables {translation = {x, y, z}, quaternion = {w, x, y, z}} (mm, w first)
// with a metatable for printing and for composing with `*`. The helpers below do the algebra so
// that scripts never multiply quaternions by hand.

#include <fmt/format.h>

#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {
namespace {

int pose(lua_State* L) {
  Vector3 translation = Vector3::Zero();
  Quaternion rotation = Quaternion::Identity();
  if (!isNone(L, 1)) translation = toVector3(L, 1);
  if (const char* why = translationProblem(translation))
    throw ArgumentError(L, 1, std::string("the translation ") + why);
  if (!isNone(L, 2)) {
    const std::vector<double> q = toNumberList(L, 2);
    if (q.size() != 4) throw ArgumentError(L, 2, "quaternion {w, x, y, z} expected");
    const std::optional<Quaternion> unit = unitQuaternion(q[0], q[1], q[2], q[3]);
    if (!unit)
      throw ArgumentError(L, 2, "the quaternion is zero or not finite: it names no rotation");
    rotation = *unit;
    rotation.normalize();
  }
  pushPose(L, makeTransform(translation, rotation));
  return 1;
}

int identity(lua_State* L) {
  pushPose(L, Transform::Identity());
  return 1;
}

int axisAngle(lua_State* L) {
  const Vector3 axis = toVector3(L, 1);
  const double angle = toNumber(L, 2);
  const Vector3 translation = isNone(L, 3) ? Vector3::Zero() : toVector3(L, 3);
  if (axis.norm() < 1e-12) throw ArgumentError(L, 1, "the axis is zero");
  pushPose(L, makeTransform(translation, Quaternion(Eigen::AngleAxisd(angle, axis.normalized()))));
  return 1;
}

// graspkit.look_at(eye, target [, up = {0, 0, 1}]): a pose at `eye` whose z axis points at
// `target` (a hand's approach direction, a camera's view), whose y axis is `up` made square to
// z, and x = y cross z. An `up` along the line of sight is replaced by the world y axis (or x).
int lookAt(lua_State* L) {
  const Vector3 eye = toVector3(L, 1);
  const Vector3 target = toVector3(L, 2);
  Vector3 up = isNone(L, 3) ? Vector3::UnitZ() : toVector3(L, 3);
  const Vector3 z = target - eye;
  if (z.norm() < 1e-9) throw ArgumentError(L, 2, "the target is at the eye");
  const Vector3 forward = z.normalized();
  if (up.norm() < 1e-12) throw ArgumentError(L, 3, "up is zero");
  for (const Vector3& fallback : {Vector3::UnitY().eval(), Vector3::UnitX().eval()}) {
    if (up.normalized().cross(forward).norm() > 1e-6) break;
    up = fallback;
  }
  const Vector3 x = up.cross(forward).normalized();
  const Vector3 y = forward.cross(x);
  Transform pose = Transform::Identity();
  pose.linear().col(0) = x;
  pose.linear().col(1) = y;
  pose.linear().col(2) = forward;
  pose.translation() = eye;
  pushPose(L, pose);
  return 1;
}

int compose(lua_State* L) {
  const int count = lua_gettop(L);
  if (count < 1) throw ArgumentError(L, 1, "pose expected, got no value");
  Transform product = toPose(L, 1);
  for (int i = 2; i <= count; ++i) product = product * toPose(L, i);
  pushPose(L, product);
  return 1;
}

int inverse(lua_State* L) {
  pushPose(L, toPose(L, 1).inverse());
  return 1;
}

int transformPoint(lua_State* L) {
  pushVector3(L, toPose(L, 1) * toVector3(L, 2));
  return 1;
}

int rotateVector(lua_State* L) {
  pushVector3(L, toPose(L, 1).linear() * toVector3(L, 2));
  return 1;
}

// The distance between two poses: translation (mm) and rotation angle (rad, in [0, pi]).
int poseDistance(lua_State* L) {
  const Transform a = toPose(L, 1);
  const Transform b = toPose(L, 2);
  const Quaternion qa(a.rotation());
  const Quaternion qb(b.rotation());
  lua_pushnumber(L, (a.translation() - b.translation()).norm());
  lua_pushnumber(L, qa.angularDistance(qb));
  return 2;
}

int poseToString(lua_State* L) {
  const Transform p = toPose(L, 1);
  const Quaternion q(p.rotation());
  const Vector3& t = p.translation();
  const std::string text = fmt::format(
      "pose(translation = {{{:.6g}, {:.6g}, {:.6g}}}, quaternion = {{{:.6g}, {:.6g}, "
      "{:.6g}, {:.6g}}})",
      t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z());
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

}  // namespace

void openPoseFunctions(lua_State* L) {
  luaL_newmetatable(L, "graspkit.Pose");
  lua_pushcfunction(L, guarded<poseToString>);
  lua_setfield(L, -2, "__tostring");
  lua_pushcfunction(L, guarded<compose>);
  lua_setfield(L, -2, "__mul");
  // Locked, as the classes' are: a script that could reach this shared table could give every
  // pose made afterwards a finalizer, which runs where no time limit reaches.
  lua_pushliteral(L, "graspkit.Pose");
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  const luaL_Reg functions[] = {
      {"pose", guarded<pose>},
      {"identity", guarded<identity>},
      {"axis_angle", guarded<axisAngle>},
      {"compose", guarded<compose>},
      {"look_at", guarded<lookAt>},
      {"inverse", guarded<inverse>},
      {"transform_point", guarded<transformPoint>},
      {"rotate_vector", guarded<rotateVector>},
      {"pose_distance", guarded<poseDistance>},
      {nullptr, nullptr},
  };
  luaL_setfuncs(L, functions, 0);
}

}  // namespace graspkit::lua
