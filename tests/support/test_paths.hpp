#pragma once
// Paths the tests need: the project's own files and the shared GraspIt! corpus beside the
// checkout (../shared), which GRASPKIT_SHARED may override.

#include <filesystem>
#include <optional>

namespace graspkit::test {

std::filesystem::path sourceDir();   // the project root
std::filesystem::path modelsDir();   // <root>/models
std::filesystem::path scratchDir();  // a fresh folder for files a test writes

// ../shared, or GRASPKIT_SHARED; nullopt (with a loud message on stderr) when absent.
std::optional<std::filesystem::path> sharedDir();
std::optional<std::filesystem::path> graspitDataDir();    // <shared>/graspit-data
std::optional<std::filesystem::path> referenceFigures();  // <shared>/reference/graspit-figures.json

}  // namespace graspkit::test

// Skips the current test loudly when the shared corpus is absent (CI always has it).
#define GRASPKIT_REQUIRE_SHARED()                                                            \
  do {                                                                                       \
    if (!::graspkit::test::sharedDir())                                                      \
      GTEST_SKIP() << "SKIPPED: ../shared (GraspIt! corpus) not found; set GRASPKIT_SHARED"; \
  } while (0)
