// Crashes in a static constructor, while dlopen itself runs, before the loader sees a descriptor.
#include <cstdlib>

#include "graspkit/plugin/plugin.hpp"

namespace {
struct AbortsWhenConstructed {
  AbortsWhenConstructed() { std::abort(); }
};
const AbortsWhenConstructed crash;

void registerNothing(graspkit::Registrar&) {}
}  // namespace

GRASPKIT_PLUGIN("aborts_on_open", "1.0", registerNothing)
