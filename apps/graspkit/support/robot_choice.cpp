#include "support/robot_choice.hpp"

#include "graspkit/base/error.hpp"
#include "graspkit/host/subject.hpp"

namespace graspkit::cli {
namespace {

// The host layer's choice, its error prefixed with the flag when the flag was given.
template <typename Choose>
auto withFlag(const char* flag, const std::string& value, Choose choose) {
  try {
    return choose();
  } catch (const Error& e) {
    if (value.empty()) throw;
    std::string message = flag;
    message.append(" ").append(e.what());
    throw Error(message);
  }
}

}  // namespace

int chooseHand(const World& world, const std::string& robot) {
  return withFlag("--robot", robot, [&] { return host::handNamed(world, robot); });
}

BodyRef chooseObject(const World& world, const std::string& object) {
  return withFlag("--object", object, [&] { return host::objectNamed(world, object); });
}

}  // namespace graspkit::cli
