// A second plugin calling itself "corpus_good".
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerImpostor(graspkit::Registrar& registrar) {
  registrar.addRobotType("ImpostorType", corpus::palmIgnoresFirstLink());
}
}  // namespace

GRASPKIT_PLUGIN("corpus_good", "9.9.9", registerImpostor)
