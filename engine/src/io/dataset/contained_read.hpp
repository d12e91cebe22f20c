#pragma once
// Internal: running a reader that is not safe against hostile bytes in a forked child process.
// libhdf5 trusts the sizes and offsets a file gives (the dataset fuzz target found it reading past
// its buffers and asking for exabytes within seconds); graspkit checks what it can, and runs the
// rest of the read where a crash, an abort or a runaway ends only the child.

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

namespace graspkit {

// Runs `read` in a forked child and returns the bytes it returned. A graspkit::Error the child
// throws is thrown here with its message. A child that crashes, exits, runs past `timeout` (then
// killed) or runs out of memory (its address space is bounded by `memoryLimit` bytes, except
// under AddressSanitizer, which needs its own) becomes a graspkit::Error naming `file`. Throws
// too when no child can be started.
std::string readInChild(const std::function<std::string()>& read, const std::filesystem::path& file,
                        std::chrono::seconds timeout, std::size_t memoryLimit);

}  // namespace graspkit
