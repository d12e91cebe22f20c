#pragma once
// A request's setting outside what it may be (a step budget of 0, a mode a planner does not
// have, steps and seconds both given): the caller's mistake, not the input files'. The host
// layer throws it so that each front end can report it as its own kind of bad argument (Python's
// ValueError, the C ABI's GRASPKIT_ERROR_INVALID_ARGUMENT); the program prints it as any error.

#include "graspkit/base/error.hpp"

namespace graspkit::host {

class InvalidSetting : public Error {
 public:
  using Error::Error;
};

}  // namespace graspkit::host
