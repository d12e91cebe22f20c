#pragma once
// The `graspkit` Lua module: one open function per part of the API, each in its own file.

#include <lua.hpp>

#include <string>

namespace graspkit::lua {

// Pushes the module table (registering every class's metatable first).
int openGraspkitModule(lua_State* L);

// Each adds its functions to the module table on top of the stack and registers its classes.
void openPoseFunctions(lua_State* L);     // pose.cpp
void openWorldFunctions(lua_State* L);    // world_binding.cpp
void openPluginFunctions(lua_State* L);   // plugin_binding.cpp
void openJsonFunctions(lua_State* L);     // json_binding.cpp
void openPlannerFunctions(lua_State* L);  // planner_binding.cpp
void openDatasetFunctions(lua_State* L);  // dataset_binding.cpp
void registerBodyClass(lua_State* L);     // body_binding.cpp
void registerRobotClass(lua_State* L);    // robot_binding.cpp
void registerGraspClass(lua_State* L);    // grasp_binding.cpp

// Hands progress to the host's ScriptOptions::progress, if it set one: `fraction` done (clamped
// to 0..1; 1 ends the task) and a line of text.
void reportProgress(lua_State* L, double fraction, const std::string& text);

}  // namespace graspkit::lua
