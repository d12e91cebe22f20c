// libFuzzer target for the plan JSON reader of render, export, view and validate
// (apps/graspkit/support/scene_frames.cpp): any bytes as a plan must give frames whose worlds hold
// finite, rigid poses, or a graspkit::Error. The fuzzer runs in the project's models folder, so
// a plan naming "worlds/gripper_box.xml" (as the seeds do) reaches the grasp-by-grasp reading.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "support/scene_frames.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& planFile() {
  static const fs::path file = [] {
    std::string pattern = (fs::temp_directory_path() / "graspkit_plan_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    return fs::path(pattern) / "plan.json";
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  graspkit::setWarningHandler([](const graspkit::Warning&) {});
  if (::chdir(GRASPKIT_FUZZ_MODELS) != 0) std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(planFile(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  graspkit::cli::FrameSource source;
  source.input = planFile();
  try {
    for (const graspkit::cli::SceneFrame& frame : graspkit::cli::loadFrames(source))
      for (int r = 0; r < frame.world.robotCount(); ++r)
        if (!frame.world.robot(r).pose().matrix().allFinite()) std::abort();
  } catch (const graspkit::Error&) {
    // Refused with a located error: the expected outcome for most inputs.
  }
  return 0;
}
