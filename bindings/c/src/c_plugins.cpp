// Plugins: scan the search path, load one file, read what was found.

#include <mutex>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/plugin/plugin_loader.hpp"
#include "graspkit/plugin/registry.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

// The last scan's list, shared by every thread (the registry is global too).
std::mutex scan_mutex;
std::vector<PluginInfo>& lastScan() {
  static std::vector<PluginInfo> scan;
  return scan;
}

}  // namespace

extern "C" {

graspkit_status graspkit_plugins_scan(size_t* count) {
  return guarded([&] {
    require(count, "count");
    std::vector<PluginInfo> found = Registry::global().plugins().survey();
    std::lock_guard lock(scan_mutex);
    lastScan() = std::move(found);
    *count = lastScan().size();
  });
}

graspkit_status graspkit_plugin_load(const char* path) {
  return guarded([&] { Registry::global().plugins().load(require(path, "path")); });
}

graspkit_status graspkit_plugin_info(size_t index, char* name, size_t name_capacity, int* loaded,
                                     char* error, size_t error_capacity) {
  return guarded([&] {
    require(loaded, "loaded");
    std::lock_guard lock(scan_mutex);
    const std::vector<PluginInfo>& scan = lastScan();
    if (index >= scan.size())
      throw Failure{
          GRASPKIT_ERROR_OUT_OF_RANGE,
          fmt::format("plugin {} does not exist (the last scan found {})", index, scan.size())};
    const PluginInfo& info = scan[index];
    // Both strings are written before a too-small buffer is reported.
    graspkit_status status = GRASPKIT_OK;
    try {
      copyString(info.name, name, name_capacity, nullptr);
    } catch (const Failure& f) {
      status = f.status;
    }
    try {
      copyString(info.loaded ? std::string() : info.error, error, error_capacity, nullptr);
    } catch (const Failure& f) {
      if (error_capacity > 0) status = f.status;  // no buffer given: the caller does not want it
    }
    *loaded = info.loaded ? 1 : 0;
    if (status != GRASPKIT_OK)
      throw Failure{status, "the plugin's name or error does not fit the buffer given"};
  });
}

graspkit_status graspkit_plugin_search_path(char* buffer, size_t capacity, size_t* length) {
  return guarded([&] {
    copyString(Registry::global().plugins().describeSearchPath(), buffer, capacity, length);
  });
}

}  // extern "C"
