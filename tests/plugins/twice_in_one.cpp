// Registers the same robot type twice itself.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerTwice(graspkit::Registrar& registrar) {
  registrar.addRobotType("TwiceType", corpus::palmIgnoresFirstLink());
  registrar.addRobotType("TwiceType", corpus::palmIgnoresFirstLink());
}
}  // namespace

GRASPKIT_PLUGIN("twice_in_one", "1.0", registerTwice)
