// The simann plugin: GraspIt!'s eigengrasp simulated-annealing planner.

#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"
#include "simann_planner.hpp"

namespace {

void registerSimAnn(graspkit::Registrar& registrar) {
  registrar.addPlanner("simann", graspkit::simann::makeSimAnnPlanner);
}

}  // namespace

GRASPKIT_PLUGIN("simann", "1.0.0", registerSimAnn)
