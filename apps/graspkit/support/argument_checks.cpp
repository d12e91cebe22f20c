#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>
#include <stdexcept>
#include "graspkit/base/error.hpp"
#include "support/argument_checks.hpp"

namespace graspkit::cli {

// CLI11's ExistingFile says "File does not exist"; this one says which case it is.
CLI::Validator existingFile() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        std::error_code ec;
        const auto status = std::filesystem::status(name, ec);
        if (!std::filesystem::exists(status)) return "no such file: " + name;
        if (std::filesystem::is_directory(status)) return name + " is a folder, not a file";
        return {};
      },
      "FILE");
}

// A seed is a whole number from 0 to 2^64 - 1, written as one: CLI11 would take "-1" as
// 2^64 - 1 and saturate 2^64 to it, so two different seeds would give the same run.
CLI::Validator seedNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size())
          return "'" + text + "' is not a seed (a whole number from 0 to 18446744073709551615)";
        return {};
      },
      "SEED");
}

// A finite number above zero (CLI11's PositiveNumber lets NaN through).
CLI::Validator positiveFinite() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
            !std::isfinite(value) || !(value > 0.0))
          return "'" + text + "' is not a finite number above zero";
        return {};
      },
      "POSITIVE");
}

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
