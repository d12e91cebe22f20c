// The approach plugin: grasps found by bringing the open hand straight in toward the object
// from evenly spread directions.

#include "approach_planner.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

void registerApproach(graspkit::Registrar& registrar) {
  registrar.addPlanner("approach", graspkit::approach::makeApproachPlanner);
}

}  // namespace

GRASPKIT_PLUGIN("approach", "1.0.0", registerApproach)
