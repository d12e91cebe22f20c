// Ends the process with exit(3) from its register function.
#include <cstdlib>

#include "graspkit/plugin/plugin.hpp"

namespace {
void registerThenExit(graspkit::Registrar&) {
  std::exit(3);
}
}  // namespace

GRASPKIT_PLUGIN("exits", "1.0", registerThenExit)
