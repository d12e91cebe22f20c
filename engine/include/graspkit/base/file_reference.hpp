#pragma once
// How a file graspkit writes names another file (a world its body and robot files, a Body XML
// its geometry, a plan its worlds, a grasp dataset its object and hand), so that the written file
// reads back from any working folder, with no --root:
// - relative to the written file's own folder when the two share a folder below the file
//   system's root (they can then move together: a project's out/ and models/), with `..` where
//   needed (`../models/objects/mug.xml`);
// - absolute otherwise (`/tmp/plan/plan_01.xml` naming `/work/graspkit/models/objects/mug.xml`).
// Both paths are taken physically (symbolic links resolved), so `..` means the same to the
// reader as to the writer.

#include <filesystem>
#include <string>
#include <string_view>

namespace graspkit {

// The text naming `target` from a file in `folder` (the empty folder is the working folder), in
// generic form ('/' separators): relative as above, or absolute.
std::string fileReference(const std::filesystem::path& target, const std::filesystem::path& folder);

// Whether `name` is explicitly relative to the file that holds it: its first component is `.`
// or `..` (`./objects/mug.xml`, `../models/mug.xml`). World files look such a name up beside
// themselves first, before --root (io/graspit/world_file.hpp).
bool isFileRelative(std::string_view name);

}  // namespace graspkit
