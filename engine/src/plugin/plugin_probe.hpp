#pragma once
// Probing plugins in a child process (internal to the plugin module). A plugin is native code
// that runs as it loads: a static constructor or register function that crashes, loops or calls
// exit() would take the host down. The loader therefore opens every plugin it has not seen
// first in a forked child, which reports each plugin's name and the names it provides over a
// pipe; only plugins that opened cleanly there are ever loaded into the host, and only the one
// that provides a needed name.

#include <chrono>
#include <filesystem>
#include <vector>

#include "graspkit/plugin/plugin_loader.hpp"

namespace graspkit::plugin {

// One child opens `files` in turn (a new child goes on after one that crashes or hangs). Returns
// one PluginInfo per file, in order: name, version and provides for a plugin that opened, else
// error, which for a crash says which signal, for exit() which status, and for a hang that the
// plugin did not finish loading within `timeout` (the child is then killed). Nothing is loaded
// into the calling process. Throws graspkit::Error when no child can be started.
std::vector<PluginInfo> probePlugins(const std::vector<std::filesystem::path>& files,
                                     std::chrono::milliseconds timeout);

}  // namespace graspkit::plugin
