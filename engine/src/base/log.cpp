#include "graspkit/base/log.hpp"

#include <cstdio>
#include <mutex>

#include <spdlog/spdlog.h>

namespace graspkit {
namespace {

std::mutex handler_mutex;
WarningHandler& currentHandler() {
  static WarningHandler handler;
  return handler;
}

// The library never writes to stdout: a host may be printing CSV or JSON there. A program that
// registers an spdlog logger named "graspkit" (the command-line program does, on stderr, with
// its -q and -v levels) gets the messages through it; any other host gets them on stderr.
std::shared_ptr<spdlog::logger> programLogger() {
  return spdlog::get("graspkit");
}

}  // namespace

std::span<const EnumName<WarningKind>> enumNames(std::type_identity<WarningKind>) {
  static constexpr EnumName<WarningKind> kNames[] = {
      {WarningKind::UnknownElement, "unknown-element"},
      {WarningKind::Geometry, "geometry"},
      {WarningKind::Mass, "mass"},
      {WarningKind::Robot, "robot"},
      {WarningKind::Eigengrasp, "eigengrasp"},
      {WarningKind::VirtualContact, "virtual-contact"},
      {WarningKind::Plugin, "plugin"},
      {WarningKind::Collision, "collision"},
      {WarningKind::Script, "script"}};
  return kNames;
}

std::string describe(const Warning& warning) {
  const std::string where = warning.where.str();
  return where.empty() ? warning.message : where + ": " + warning.message;
}

WarningHandler setWarningHandler(WarningHandler handler) {
  std::lock_guard lock(handler_mutex);
  WarningHandler previous = std::move(currentHandler());
  currentHandler() = std::move(handler);
  return previous;
}

void warn(WarningKind kind, const SourceLocation& where, const std::string& message) {
  WarningHandler handler;
  {
    std::lock_guard lock(handler_mutex);
    handler = currentHandler();
  }
  const Warning warning{kind, where, message};
  if (handler) {
    handler(warning);
  } else if (auto logger = programLogger()) {
    logger->warn("{}", describe(warning));
  } else {
    std::fprintf(stderr, "graspkit: warning: %s\n", describe(warning).c_str());
  }
}

void trace(const std::string& message) {
  if (auto logger = programLogger()) logger->debug("{}", message);
}

}  // namespace graspkit
