#pragma once
// Warnings about input that loads but is suspicious (unknown tags, open meshes, fallbacks).
// They go through one replaceable handler, so a host application or a test can capture them;
// the default handler prints them on stderr ("graspkit: warning: ..."), or through the spdlog
// logger named "graspkit" when the program has registered one. The library never writes to stdout.
// Each warning has a kind, so that a program can silence one kind and keep the others.

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/base/error.hpp"

namespace graspkit {

enum class WarningKind {
  UnknownElement,  // a tag, attribute or transform element the reader does not know; ignored
  Geometry,        // a mesh or Inventor file: no triangles, a missing File node, Coin's messages
  Mass,            // mass properties that fall back (an inertia the mesh cannot give)
  Robot,           // a robot file GraspIt! reads leniently (swapped limits, idle DOFs, ...)
  Eigengrasp,      // an eigengrasp file that does not fit the robot
  VirtualContact,  // a virtual-contact file that does not fit the robot
  Plugin,          // a plugin that does not load, or a robot type no plugin provides
  Collision,       // a hand that starts intersecting what it should grasp
  Script,          // a Lua test file that defines no tests, and the like
};

// The kinds in declaration order, and their names as the command line spells them
// ("unknown-element", "geometry", ...).
inline constexpr WarningKind kWarningKinds[] = {
    WarningKind::UnknownElement, WarningKind::Geometry,   WarningKind::Mass,
    WarningKind::Robot,          WarningKind::Eigengrasp, WarningKind::VirtualContact,
    WarningKind::Plugin,         WarningKind::Collision,  WarningKind::Script};
// unknown-element, geometry, mass, robot, eigengrasp, virtual-contact, plugin, collision, script
// (base/enum_names.hpp: nameOf, valueNamed, parseNamed).
std::span<const EnumName<WarningKind>> enumNames(std::type_identity<WarningKind>);

struct Warning {
  WarningKind kind = WarningKind::UnknownElement;
  SourceLocation where;  // empty when the warning is about no file
  std::string message;
};

using WarningHandler = std::function<void(const Warning& warning)>;

// Installs `handler` (an empty one restores the default) and returns the previous handler.
WarningHandler setWarningHandler(WarningHandler handler);

void warn(WarningKind kind, const SourceLocation& where, const std::string& message);

// "file:line: <element>: message" (or the message alone when there is no location).
std::string describe(const Warning& warning);

// A trace line for `graspkit -v` (spdlog's debug level), such as the plugin about to run: when
// native code crashes the process, the last trace line says whose code it was.
void trace(const std::string& message);

}  // namespace graspkit
