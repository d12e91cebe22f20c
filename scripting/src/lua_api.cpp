#include "lua_api.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace graspkit::lua {
namespace {

// A function called through pcall or a local has no name in its call info: find it in the
// graspkit module, as luaL_argerror finds library functions in package.loaded.
std::string functionNameInModule(lua_State* L, lua_Debug* ar) {
  std::string name = "?";
  const int top = lua_gettop(L);
  lua_getinfo(L, "f", ar);  // the function, at top + 1
  // Searches the table on top of the stack for the function; pops the table.
  auto search = [&](const std::string& prefix) {
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      if (lua_rawequal(L, -1, top + 1) && lua_type(L, -2) == LUA_TSTRING) {
        name = prefix + lua_tostring(L, -2);
      }
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  };
  if (lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE) == LUA_TTABLE &&
      lua_getfield(L, -1, "graspkit") == LUA_TTABLE) {
    search("graspkit.");
  }
  lua_settop(L, top + 1);
  // A method taken from an object (pcall(world.robot, world, 3)): its class's method table.
  if (lua_getmetatable(L, 1) && lua_getfield(L, -1, "__index") == LUA_TTABLE) search("");
  lua_settop(L, top);
  return name;
}

// Lua's own wording for a bad argument (luaL_argerror), without raising: a method's self is
// argument 0, so the numbers a user sees match what they wrote after the colon.
std::string argumentMessage(lua_State* L, int arg, const std::string& message) {
  lua_Debug ar;
  if (!lua_getstack(L, 0, &ar)) return fmt::format("bad argument #{} ({})", arg, message);
  lua_getinfo(L, "n", &ar);
  std::string called = ar.name != nullptr ? ar.name : functionNameInModule(L, &ar);
  if (ar.namewhat != nullptr && std::string(ar.namewhat) == "method") {
    --arg;
    if (arg == 0) return fmt::format("calling '{}' on bad self ({})", called, message);
  }
  return fmt::format("bad argument #{} to '{}' ({})", arg, called, message);
}

// t[key] without metamethods: an __index that raises would longjmp over the reader's C++ frames.
int rawField(lua_State* L, int table, const char* key) {
  table = lua_absindex(L, table);
  lua_pushstring(L, key);
  return lua_rawget(L, table);
}

double toFiniteNumber(lua_State* L, int arg, const char* what) {
  if (lua_type(L, arg) != LUA_TNUMBER) {
    throw ArgumentError(L, arg, fmt::format("{} expected, got {}", what, luaL_typename(L, arg)));
  }
  const double value = lua_tonumber(L, arg);
  if (!std::isfinite(value)) {
    throw ArgumentError(L, arg, fmt::format("{} must be finite, got {}", what, value));
  }
  return value;
}

// Reads a list of exactly `n` finite numbers from the table at `arg` (absolute index).
template <int N>
Eigen::Matrix<double, N, 1> toFixedList(lua_State* L, int arg, const char* what) {
  if (lua_type(L, arg) != LUA_TTABLE) {
    throw ArgumentError(L, arg, fmt::format("{} expected, got {}", what, luaL_typename(L, arg)));
  }
  const lua_Integer length = static_cast<lua_Integer>(lua_rawlen(L, arg));
  if (length != N) {
    throw ArgumentError(L, arg, fmt::format("{} needs {} numbers, got {}", what, N, length));
  }
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) {
    const int type = lua_rawgeti(L, arg, i + 1);
    const double value = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (type != LUA_TNUMBER || !std::isfinite(value)) {
      throw ArgumentError(L, arg, fmt::format("{}[{}] is not a finite number", what, i + 1));
    }
    v[i] = value;
  }
  return v;
}

}  // namespace

ArgumentError::ArgumentError(lua_State* L, int arg, const std::string& message)
    : std::runtime_error(argumentMessage(L, arg, message)) {}

int raiseError(lua_State* L) {
  luaL_where(L, 1);
  lua_insert(L, -2);
  lua_concat(L, 2);
  return lua_error(L);
}

double toNumber(lua_State* L, int arg) {
  return toFiniteNumber(L, arg, "number");
}

int toInteger(lua_State* L, int arg) {
  const double value = toFiniteNumber(L, arg, "integer");
  if (value != std::floor(value) || value < std::numeric_limits<int>::min() ||
      value > std::numeric_limits<int>::max()) {
    throw ArgumentError(L, arg, fmt::format("integer expected, got {}", value));
  }
  return static_cast<int>(value);
}

std::string toString(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TSTRING) {
    throw ArgumentError(L, arg, fmt::format("string expected, got {}", luaL_typename(L, arg)));
  }
  std::size_t length = 0;
  const char* text = lua_tolstring(L, arg, &length);
  return std::string(text, length);
}

// The operating system stops a file name at its first NUL byte, so a name holding one would open
// another file than the one every check saw.
std::string toFileName(lua_State* L, int arg) {
  std::string name = toString(L, arg);
  if (name.find('\0') != std::string::npos)
    throw ArgumentError(L, arg, "a file name may not hold a NUL byte");
  return name;
}

bool toBoolean(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TBOOLEAN) {
    throw ArgumentError(L, arg, fmt::format("boolean expected, got {}", luaL_typename(L, arg)));
  }
  return lua_toboolean(L, arg) != 0;
}

void checkTable(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TTABLE) {
    throw ArgumentError(L, arg, fmt::format("table expected, got {}", luaL_typename(L, arg)));
  }
}

bool isNone(lua_State* L, int arg) {
  return lua_isnoneornil(L, arg);
}

std::vector<double> toNumberList(lua_State* L, int arg) {
  arg = lua_absindex(L, arg);
  checkTable(L, arg);
  const auto length = static_cast<lua_Integer>(lua_rawlen(L, arg));
  std::vector<double> values(static_cast<std::size_t>(length));
  for (lua_Integer i = 0; i < length; ++i) {
    const int type = lua_rawgeti(L, arg, i + 1);
    const double value = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (type != LUA_TNUMBER || !std::isfinite(value)) {
      throw ArgumentError(L, arg, fmt::format("element {} is not a finite number", i + 1));
    }
    values[static_cast<std::size_t>(i)] = value;
  }
  return values;
}

Vector3 toVector3(lua_State* L, int arg) {
  return toFixedList<3>(L, lua_absindex(L, arg), "{x, y, z}");
}

Transform toPose(lua_State* L, int arg) {
  arg = lua_absindex(L, arg);
  if (lua_type(L, arg) != LUA_TTABLE) {
    throw ArgumentError(L, arg, fmt::format("pose expected, got {}", luaL_typename(L, arg)));
  }
  Vector3 translation = Vector3::Zero();
  Quaternion rotation = Quaternion::Identity();
  // Reject unknown keys: {position = ...} or {rotation = ...} would silently mean the identity.
  lua_pushnil(L);
  while (lua_next(L, arg) != 0) {
    lua_pop(L, 1);
    const bool known =
        lua_type(L, -1) == LUA_TSTRING && (std::string(lua_tostring(L, -1)) == "translation" ||
                                           std::string(lua_tostring(L, -1)) == "quaternion");
    if (!known) {
      lua_pop(L, 1);
      throw ArgumentError(L, arg, "a pose has only the keys 'translation' and 'quaternion'");
    }
  }
  if (rawField(L, arg, "translation") != LUA_TNIL) {
    translation = toFixedList<3>(L, lua_gettop(L), "translation {x, y, z}");
    if (const char* why = translationProblem(translation)) {
      lua_pop(L, 1);
      throw ArgumentError(L, arg, std::string("the translation ") + why);
    }
  }
  lua_pop(L, 1);
  if (rawField(L, arg, "quaternion") != LUA_TNIL) {
    const Eigen::Vector4d q = toFixedList<4>(L, lua_gettop(L), "quaternion {w, x, y, z}");
    const std::optional<Quaternion> unit = unitQuaternion(q[0], q[1], q[2], q[3]);
    if (!unit) {
      lua_pop(L, 1);
      throw ArgumentError(L, arg, "the quaternion is zero or not finite: it names no rotation");
    }
    rotation = *unit;
  }
  lua_pop(L, 1);
  return makeTransform(translation, rotation);
}

OptionsTable::OptionsTable(lua_State* L, int arg, std::vector<std::string> known)
    : L_(L), arg_(lua_absindex(L, arg)), present_(!lua_isnoneornil(L, arg)) {
  if (!present_) return;
  checkTable(L, arg_);
  lua_pushnil(L);
  while (lua_next(L, arg_) != 0) {
    lua_pop(L, 1);
    const bool ok = lua_type(L, -1) == LUA_TSTRING &&
                    std::find(known.begin(), known.end(), lua_tostring(L, -1)) != known.end();
    if (!ok) {
      std::string key = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "(not a name)";
      lua_pop(L, 1);
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw ArgumentError(L, arg_, fmt::format("unknown option '{}' (options: {})", key, list));
    }
  }
}

int OptionsTable::pushField(const char* key) const {
  if (!present_) {
    lua_pushnil(L_);
    return LUA_TNIL;
  }
  return rawField(L_, arg_, key);
}

bool OptionsTable::has(const char* key) const {
  const bool found = pushField(key) != LUA_TNIL;
  lua_pop(L_, 1);
  return found;
}

double OptionsTable::number(const char* key, double fallback) const {
  const int type = pushField(key);
  const double value = lua_tonumber(L_, -1);
  lua_pop(L_, 1);
  if (type == LUA_TNIL) return fallback;
  if (type != LUA_TNUMBER || !std::isfinite(value)) {
    throw ArgumentError(L_, arg_, fmt::format("option '{}' must be a finite number", key));
  }
  return value;
}

int OptionsTable::integer(const char* key, int fallback) const {
  const double value = number(key, fallback);
  if (value != std::floor(value) || std::abs(value) > std::numeric_limits<int>::max()) {
    throw ArgumentError(L_, arg_, fmt::format("option '{}' must be a whole number", key));
  }
  return static_cast<int>(value);
}

std::optional<Vector3> OptionsTable::vector3(const char* key) const {
  const int type = pushField(key);
  if (type == LUA_TNIL) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  Vector3 v;
  bool ok = type == LUA_TTABLE && lua_rawlen(L_, -1) == 3;
  for (int i = 0; ok && i < 3; ++i) {
    const int element = lua_rawgeti(L_, -1, i + 1);
    v[i] = lua_tonumber(L_, -1);
    lua_pop(L_, 1);
    ok = element == LUA_TNUMBER && std::isfinite(v[i]);
  }
  lua_pop(L_, 1);
  if (!ok)
    throw ArgumentError(L_, arg_,
                        fmt::format("option '{}' must be {{x, y, z}} of finite numbers", key));
  return v;
}

bool OptionsTable::boolean(const char* key, bool fallback) const {
  const int type = pushField(key);
  const bool value = lua_toboolean(L_, -1) != 0;
  lua_pop(L_, 1);
  if (type == LUA_TNIL) return fallback;
  if (type != LUA_TBOOLEAN) {
    throw ArgumentError(L_, arg_, fmt::format("option '{}' must be true or false", key));
  }
  return value;
}

std::string OptionsTable::string(const char* key, const std::string& fallback) const {
  const int type = pushField(key);
  std::string value = type == LUA_TSTRING ? lua_tostring(L_, -1) : "";
  lua_pop(L_, 1);
  if (type == LUA_TNIL) return fallback;
  if (type != LUA_TSTRING) {
    throw ArgumentError(L_, arg_, fmt::format("option '{}' must be a string", key));
  }
  return value;
}

void pushVector3(lua_State* L, const Vector3& v) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

void pushNumberList(lua_State* L, std::span<const double> values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void pushPose(lua_State* L, const Transform& pose) {
  lua_createtable(L, 0, 2);
  pushVector3(L, pose.translation());
  lua_setfield(L, -2, "translation");
  const Quaternion q(pose.rotation());
  const double values[4] = {q.w(), q.x(), q.y(), q.z()};
  pushNumberList(L, values);
  lua_setfield(L, -2, "quaternion");
  luaL_setmetatable(L, "graspkit.Pose");
}

void pushStringList(lua_State* L, const std::vector<std::string>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    lua_pushlstring(L, values[i].data(), values[i].size());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void defineClass(lua_State* L, const char* name, const luaL_Reg* methods, lua_CFunction gc,
                 lua_CFunction tostring, lua_CFunction eq) {
  luaL_newmetatable(L, name);
  lua_newtable(L);
  luaL_setfuncs(L, methods, 0);
  lua_setfield(L, -2, "__index");
  if (gc != nullptr) {
    lua_pushcfunction(L, gc);
    lua_setfield(L, -2, "__gc");
  }
  if (tostring != nullptr) {
    lua_pushcfunction(L, tostring);
    lua_setfield(L, -2, "__tostring");
  }
  if (eq != nullptr) {
    lua_pushcfunction(L, eq);
    lua_setfield(L, -2, "__eq");
  }
  lua_pushstring(L, name);
  lua_setfield(L, -2, "__name");
  lua_pushstring(L, name);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
}

}  // namespace graspkit::lua
