// Provides a robot type that the good corpus plugin already provides.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerDuplicate(graspkit::Registrar& registrar) {
  registrar.addRobotType("DuplicateOnlyType", corpus::palmIgnoresFirstLink());
  registrar.addRobotType("CorpusGripper", corpus::palmIgnoresFirstLink());
}
}  // namespace

GRASPKIT_PLUGIN("duplicate_type", "1.0", registerDuplicate)
