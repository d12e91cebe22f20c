#include "graspkit/error.hpp"

namespace graspkit {

std::string SourceLocation::str() const {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) out += ":" + std::to_string(line);
  if (!element.empty()) out += ": <" + element + ">";
  return out;
}

Error::Error(SourceLocation where, const std::string& message)
    : std::runtime_error(where.file.empty() && where.element.empty() ? message
                                                                     : where.str() + ": " + message),
      where_(std::move(where)),
      message_(message) {}

}  // namespace graspkit
