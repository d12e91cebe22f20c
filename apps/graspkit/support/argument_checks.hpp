#pragma once
// The checks of the commands' arguments that CLI11 lacks, and lists of numbers.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace graspkit::cli {

// The check of a file argument: "no such file: NAME" or "NAME is a folder, not a file".
CLI::Validator existingFile();
CLI::Validator seedNumber();      // 0 .. 2^64 - 1, digits only
CLI::Validator positiveFinite();  // > 0 and finite

// "1,2.5,-3" -> {1, 2.5, -3}; throws graspkit::Error naming `option` for anything else
// (empty items, trailing text, NaN or infinity).
std::vector<double> parseNumberList(const std::string& text, const std::string& option);

}  // namespace graspkit::cli
