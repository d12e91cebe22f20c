// libFuzzer target for the list planner's hand-state JSON (what `plan --out` writes and `--planner
// list --set file=...` reads): any bytes give hand states with finite poses and unit
// quaternions, or a graspkit::Error.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "hand_state_file.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& scratchFile() {
  static const fs::path file = [] {
    std::string pattern = (fs::temp_directory_path() / "graspkit_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    return fs::path(pattern) / "states.json";
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(scratchFile(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    for (const auto& state : graspkit::list::readHandStates(scratchFile())) {
      if (!state.pose.matrix().allFinite()) std::abort();
      for (const double dof : state.dofs)
        if (!std::isfinite(dof)) std::abort();
    }
  } catch (const graspkit::Error&) {
  }
  return 0;
}
