#pragma once
// Warnings about input that loads but is suspicious (unknown tags, open meshes, fallbacks).
// They go through one replaceable handler, so a host application or a test can capture them;
// the default handler prints them on stderr ("graspkit: warning: ..."), or through the spdlog
// logger named "graspkit" when the program has registered one. The library never writes to stdout.

#include <functional>
#include <string>

#include "graspkit/error.hpp"

namespace graspkit {

using WarningHandler = std::function<void(const SourceLocation& where, const std::string& message)>;

// Installs `handler` (an empty one restores the default) and returns the previous handler.
WarningHandler setWarningHandler(WarningHandler handler);

void warn(const SourceLocation& where, const std::string& message);

// A trace line for `graspkit -v` (spdlog's debug level), such as the plugin about to run: when
// native code crashes the process, the last trace line says whose code it was.
void trace(const std::string& message);

}  // namespace graspkit
