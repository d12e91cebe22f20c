#include "graspkit/log.hpp"

#include <mutex>

#include <spdlog/spdlog.h>

namespace graspkit {
namespace {

std::mutex handler_mutex;
WarningHandler& currentHandler() {
  static WarningHandler handler;
  return handler;
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
  } else {
    spdlog::warn("{}: {}", where.str(), message);
  }
}

void trace(const std::string& message) {
  spdlog::debug("{}", message);
}

}  // namespace graspkit
