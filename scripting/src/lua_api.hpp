#pragma once
// The glue every binding uses: C functions that may throw, argument readers that throw instead
// of raising, and C++ objects kept in full userdata.
//
// Why the care: Lua raises errors with longjmp, which skips C++ destructors. So no binding calls
// a raising Lua function (luaL_check*, lua_error) while C++ objects are alive. Bindings are
// written as plain C++ that throws; guarded<> catches, lets the stack unwind, and only then
// raises the Lua error (with the caller's file and line in front of the message).

#include <lua.hpp>

#include <new>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::lua {

// A wrong argument: becomes "bad argument #n to 'name' (message)", as Lua words it.
class ArgumentError : public std::runtime_error {
 public:
  ArgumentError(lua_State* L, int arg, const std::string& message);
};

// Raises the pending message (on top of the stack) as a Lua error located at the caller.
int raiseError(lua_State* L);

template <lua_CFunction F>
int guarded(lua_State* L) {
  try {
    return F(L);
  } catch (const std::exception& e) {
    lua_pushstring(L, e.what());
  } catch (...) {
    // A plugin's own exception type: caught here, or it would cross Lua's C frames.
    lua_pushliteral(L, "an exception that is not a std::exception (from a plugin's code?)");
  }
  return raiseError(L);  // every C++ local of F is gone by now
}

// Argument readers. `arg` is the stack index; errors name it.
double toNumber(lua_State* L, int arg);                   // a finite number
int toInteger(lua_State* L, int arg);                     // a whole number in int range
std::string toString(lua_State* L, int arg);              // a string (numbers are not converted)
std::string toFileName(lua_State* L, int arg);            // a string without NUL bytes
bool toBoolean(lua_State* L, int arg);                    // true or false
void checkTable(lua_State* L, int arg);                   // a table
std::vector<double> toNumberList(lua_State* L, int arg);  // {n1, n2, ...}, every one finite
Vector3 toVector3(lua_State* L, int arg);                 // {x, y, z}
Transform toPose(lua_State* L, int arg);  // {translation = {x,y,z}, quaternion = {w,x,y,z}}
bool isNone(lua_State* L, int arg);       // absent or nil

// Optional fields of an options table at `arg` (absent or nil table: the default). Unknown keys
// are an error, so a misspelt option never goes unnoticed.
class OptionsTable {
 public:
  OptionsTable(lua_State* L, int arg, std::vector<std::string> known);
  double number(const char* key, double fallback) const;
  int integer(const char* key, int fallback) const;
  bool boolean(const char* key, bool fallback) const;
  std::string string(const char* key, const std::string& fallback) const;
  std::optional<Vector3> vector3(const char* key) const;  // {x, y, z} of finite numbers
  bool has(const char* key) const;

 private:
  int pushField(const char* key) const;  // pushes the field, returns its type
  lua_State* L_;
  int arg_;
  bool present_;
};

// Results.
void pushVector3(lua_State* L, const Vector3& v);
void pushNumberList(lua_State* L, std::span<const double> values);
void pushPose(lua_State* L, const Transform& pose);  // a pose table with the Pose metatable
void pushStringList(lua_State* L, const std::vector<std::string>& values);

// C++ objects in full userdata: T is constructed in place and destroyed by __gc. The box records
// T's type and whether the object still lives, so that a __gc reached some other way than by
// the collector (scripts cannot reach the metatables, but a host might) destroys only a live T,
// once, and a method called on a destroyed object is an error, never a use after free.
template <class T>
inline const char kObjectTag = 0;

template <class T>
struct ObjectBox {
  template <class... Args>
  explicit ObjectBox(Args&&... args) : object(std::forward<Args>(args)...) {}
  const void* tag = &kObjectTag<T>;
  bool alive = true;
  T object;
};

// The box at `arg` if it is a full userdata holding a T (alive or not), else null.
template <class T>
ObjectBox<T>* boxAt(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TUSERDATA || lua_rawlen(L, arg) < sizeof(ObjectBox<T>))
    return nullptr;
  auto* box = static_cast<ObjectBox<T>*>(lua_touserdata(L, arg));
  return box->tag == &kObjectTag<T> ? box : nullptr;
}

template <class T, class... Args>
T& newObject(lua_State* L, const char* metatable, Args&&... args) {
  void* memory = lua_newuserdatauv(L, sizeof(ObjectBox<T>), 0);
  auto* box = new (memory) ObjectBox<T>(std::forward<Args>(args)...);
  luaL_setmetatable(L, metatable);
  return box->object;
}

template <class T>
int destroyObject(lua_State* L) {
  if (ObjectBox<T>* box = boxAt<T>(L, 1); box != nullptr && box->alive) {
    box->alive = false;
    box->object.~T();
  }
  return 0;
}

// The live object at `arg` if it has `metatable`, else null.
template <class T>
T* testObject(lua_State* L, int arg, const char* metatable) {
  if (luaL_testudata(L, arg, metatable) == nullptr) return nullptr;
  ObjectBox<T>* box = boxAt<T>(L, arg);
  return box != nullptr && box->alive ? &box->object : nullptr;
}

// The object at `arg` if it has `metatable`; throws ArgumentError expecting `expected` otherwise.
template <class T>
T& toObject(lua_State* L, int arg, const char* metatable, const char* expected) {
  if (luaL_testudata(L, arg, metatable) == nullptr) {
    throw ArgumentError(L, arg, std::string(expected) + " expected, got " + luaL_typename(L, arg));
  }
  ObjectBox<T>* box = boxAt<T>(L, arg);
  if (box == nullptr || !box->alive)
    throw ArgumentError(L, arg, std::string(expected) + " expected, got a destroyed one");
  return box->object;
}

// Makes metatable `name` with `methods` reachable through __index, plus the given metamethods
// (each may be null). The metatable is locked: getmetatable() on an object gives the class name,
// not the table, so no script can call __gc or change a method.
void defineClass(lua_State* L, const char* name, const luaL_Reg* methods, lua_CFunction gc,
                 lua_CFunction tostring, lua_CFunction eq = nullptr);

}  // namespace graspkit::lua
