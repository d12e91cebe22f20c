// Crashes (SIGABRT) in its register function: probed in a child, it must not take the host down.
#include <cstdlib>

#include "graspkit/plugin/plugin.hpp"

namespace {
void registerThenAbort(graspkit::Registrar&) {
  std::abort();
}
}  // namespace

GRASPKIT_PLUGIN("aborts", "1.0", registerThenAbort)
