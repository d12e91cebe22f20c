// Built for an ABI this engine does not speak.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerNothing(graspkit::Registrar& registrar) {
  registrar.addRobotType("WrongAbiType", corpus::palmIgnoresFirstLink());
}
}  // namespace

extern "C" __attribute__((visibility("default"))) const graspkit_plugin_descriptor*
graspkit_plugin_v1() {
  static const graspkit_plugin_descriptor descriptor{999u, sizeof(graspkit_plugin_descriptor),
                                                     "wrong_abi", "1", registerNothing};
  return &descriptor;
}
