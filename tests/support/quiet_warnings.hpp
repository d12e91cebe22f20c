#pragma once
// Silences load warnings for the life of the object (GraspIt!'s corpus has many unknown tags),
// restoring the previous handler afterwards.

#include "graspkit/base/log.hpp"

namespace graspkit::test {

struct QuietWarnings {
  QuietWarnings() : previous(setWarningHandler([](const Warning&) {})) {}
  ~QuietWarnings() { setWarningHandler(previous); }
  QuietWarnings(const QuietWarnings&) = delete;
  QuietWarnings& operator=(const QuietWarnings&) = delete;
  WarningHandler previous;
};

}  // namespace graspkit::test
