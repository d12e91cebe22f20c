#pragma once
// The one way the engine and its programs replace a file: never half a file, never silently.
//
// writeFileAtomically() writes the text to an unnamed file in the target's folder (Linux
// O_TMPFILE), flushes it to the disk (fsync), names it "<target>.tmp<pid>" (".graspkit.tmp<pid>"
// when the target's name is too long to extend), renames it over the target and flushes the
// folder. After a crash or a power cut the target holds the old text or the new, whole; a process
// killed while it writes leaves nothing behind (only a kill in the instant between naming and
// renaming leaves the named file). On a file system without O_TMPFILE the named file is written
// directly, and a kill then leaves it. It refuses a target that is read-only (its owner-write
// permission is off: the user protected it) or that is not a regular file (a FIFO, a device
// such as /dev/null, a folder: a rename would put a plain file in its place, and as root destroy
// the device), and reports every failure with the operating
// system's reason; the temporary file is removed on failure.

#include <filesystem>
#include <string_view>

namespace graspkit {

// Throws graspkit::Error naming `file` when its path is not UTF-8 (it could not be read back) or
// it exists and is not a writable regular file (the checks writeFileAtomically makes first;
// writers that rename their own temporaries use it).
void checkReplaceable(const std::filesystem::path& file);

// Creates `folder` and the folders above it where missing (an output folder a command writes
// into). Throws graspkit::Error naming the folder and the operating system's reason when it
// cannot: a file, a FIFO or /proc standing where a folder must be is bad input, not a crash.
void createOutputFolder(const std::filesystem::path& folder);

// Throws graspkit::Error naming `file` and the reason.
void writeFileAtomically(const std::filesystem::path& file, std::string_view text);

}  // namespace graspkit
