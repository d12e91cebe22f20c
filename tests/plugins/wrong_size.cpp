// Claims a descriptor larger than this engine's: built against a different header.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerNothing(graspkit::Registrar& registrar) {
  registrar.addRobotType("WrongSizeType", corpus::palmIgnoresFirstLink());
}
}  // namespace

extern "C" __attribute__((visibility("default"))) const graspkit_plugin_descriptor*
graspkit_plugin_v1() {
  static const graspkit_plugin_descriptor descriptor{GRASPKIT_PLUGIN_ABI_VERSION,
                                                     sizeof(graspkit_plugin_descriptor) + 16,
                                                     "wrong_size", "1", registerNothing};
  return &descriptor;
}
