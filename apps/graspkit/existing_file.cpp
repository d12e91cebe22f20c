#include <filesystem>
#include <system_error>

#include "commands.hpp"

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

}  // namespace graspkit::cli
