#include "graspkit/base/error.hpp"

#include <fmt/format.h>

namespace graspkit {

std::string SourceLocation::str() const {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) out += fmt::format(":{}", line);
  if (!element.empty()) out += fmt::format(": <{}>", element);
  return out;
}

Error::Error(SourceLocation where, const std::string& message)
    : std::runtime_error(
          where.file.empty() && where.element.empty() ? message : where.str() + ": " + message),
      where_(std::move(where)),
      message_(message) {}

}  // namespace graspkit
