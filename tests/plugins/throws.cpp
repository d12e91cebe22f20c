// Registers one type, then throws: the loader must keep neither.
#include <stdexcept>

#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerThenThrow(graspkit::Registrar& registrar) {
  registrar.addRobotType("HalfRegisteredType", corpus::palmIgnoresFirstLink());
  throw std::runtime_error("calibration table missing");
}
}  // namespace

GRASPKIT_PLUGIN("throws", "1.0", registerThenThrow)
