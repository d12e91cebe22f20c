#include "graspkit/log.hpp"

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

WarningHandler setWarningHandler(WarningHandler handler) {
  std::lock_guard lock(handler_mutex);
  WarningHandler previous = std::move(currentHandler());
  currentHandler() = std::move(handler);
  return previous;
}

void warn(const SourceLocation& where, const std::string& message) {
  WarningHandler handler;
  {
    std::lock_guard lock(handler_mutex);
    handler = currentHandler();
  }
  if (handler) {
    handler(where, message);
  } else if (auto logger = programLogger()) {
    logger->warn("{}: {}", where.str(), message);
  } else {
    const std::string prefix = where.str();
    std::fprintf(stderr, "graspkit: warning: %s%s%s\n", prefix.c_str(), prefix.empty() ? "" : ": ",
                 message.c_str());
  }
}

void trace(const std::string& message) {
  if (auto logger = programLogger()) logger->debug("{}", message);
}

}  // namespace graspkit
