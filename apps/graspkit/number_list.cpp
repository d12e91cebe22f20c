#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "commands.hpp"
#include "graspkit/error.hpp"

namespace graspkit::cli {

std::vector<double> parseNumberList(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string token = text.substr(start, comma - start);
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(token, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != token.size() || !std::isfinite(value)) {
      throw Error(fmt::format("{}: '{}' is not a number", option, token));
    }
    values.push_back(value);
    start = comma + 1;
  }
  return values;
}

}  // namespace graspkit::cli
