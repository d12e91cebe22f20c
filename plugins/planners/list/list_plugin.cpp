// The list plugin: GraspIt!'s list planner, which ranks a given list of hand states.

#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"
#include "list_planner.hpp"

namespace {

void registerList(graspkit::Registrar& registrar) {
  registrar.addPlanner("list", graspkit::list::makeListPlanner);
}

}  // namespace

GRASPKIT_PLUGIN("list", "1.0.0", registerList)
