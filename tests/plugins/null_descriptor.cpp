// The entry point exists but returns no descriptor.
#include "graspkit/plugin/plugin.hpp"

extern "C" __attribute__((visibility("default"))) const graspkit_plugin_descriptor*
graspkit_plugin_v1() {
  return nullptr;
}
