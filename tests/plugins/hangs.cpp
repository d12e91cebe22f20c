// Never returns from its register function.
#include <unistd.h>

#include "graspkit/plugin/plugin.hpp"

namespace {
void registerForever(graspkit::Registrar&) {
  for (;;) ::pause();
}
}  // namespace

GRASPKIT_PLUGIN("hangs", "1.0", registerForever)
