// A robot type with an empty name.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerUnnamed(graspkit::Registrar& registrar) {
  registrar.addRobotType("", corpus::palmIgnoresFirstLink());
}
}  // namespace

GRASPKIT_PLUGIN("empty_names", "1.0", registerUnnamed)
