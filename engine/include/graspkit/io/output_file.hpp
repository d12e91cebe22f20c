#pragma once
// The one way the engine and its programs replace a file: never half a file, never silently.
//
// writeFileAtomically() writes the text to a temporary file beside the target, flushes it to the
// disk (fsync), renames it over the target and flushes the folder, so that after a crash or a
// power cut the target holds the old text or the new, whole. It refuses a target that is
// read-only (its owner-write permission is off: the user protected it) and reports every failure
// with the operating system's reason; the temporary file is removed on failure. A process
// killed while writing leaves its temporary file (named "<target>.tmp<pid>", or
// ".graspkit.tmp<pid>" when the target's name is too long to extend).

#include <filesystem>
#include <string_view>

namespace graspkit {

// Throws graspkit::Error naming `file` and the reason.
void writeFileAtomically(const std::filesystem::path& file, std::string_view text);

}  // namespace graspkit
