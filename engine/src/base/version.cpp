#include "graspkit/base/version.hpp"

namespace graspkit {

const char* engineVersion() {
  return GRASPKIT_VERSION;
}

}  // namespace graspkit
