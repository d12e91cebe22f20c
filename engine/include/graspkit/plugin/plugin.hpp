#pragma once
// What a plugin exports. A plugin is a shared object (a CMake MODULE library) with one C symbol,
// `graspkit_plugin_v1`, returning a descriptor: the ABI version and descriptor size it was built
// with (the loader refuses any mismatch), its name and version, and the function that registers
// its named factories (robot types, quality measures, ...) with a Registrar.
//
// A plugin's source file ends with
//
//   GRASPKIT_PLUGIN("barrett", "1.0.0", registerBarrett)
//
// where `void registerBarrett(graspkit::Registrar&)` adds its factories. The function may throw
// graspkit::Error (or any std::exception): the loader then registers none of its factories.

#include <cstdint>

namespace graspkit {
class Registrar;
}

// Bump when anything a plugin sees changes layout: this descriptor, Registrar, RobotType,
// RobotModel, QualityMeasure, SearchEnergy, Planner and the planning structs.
// 2: Registrar gained addSearchEnergy and addPlanner.
// 3: RobotType gained closeMotion.
#define GRASPKIT_PLUGIN_ABI_VERSION 3u
#define GRASPKIT_PLUGIN_SYMBOL "graspkit_plugin_v1"

extern "C" {

struct graspkit_plugin_descriptor {
  std::uint32_t abi_version;      // GRASPKIT_PLUGIN_ABI_VERSION as the plugin was built
  std::uint32_t descriptor_size;  // sizeof(graspkit_plugin_descriptor) as the plugin was built
  const char* name;               // unique among loaded plugins, e.g. "barrett"
  const char* version;            // the plugin's own version, recorded in saved results
  void (*register_factories)(graspkit::Registrar& registrar);
};

using graspkit_plugin_entry = const graspkit_plugin_descriptor* (*)();

}  // extern "C"

#define GRASPKIT_PLUGIN(plugin_name, plugin_version, register_function)               \
  extern "C" __attribute__((visibility("default"))) const graspkit_plugin_descriptor* \
  graspkit_plugin_v1() {                                                              \
    static const graspkit_plugin_descriptor descriptor{                               \
        GRASPKIT_PLUGIN_ABI_VERSION, sizeof(graspkit_plugin_descriptor), plugin_name, \
        plugin_version, register_function};                                           \
    return &descriptor;                                                               \
  }
