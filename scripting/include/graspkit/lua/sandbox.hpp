#pragma once
// What a scenario script may touch. A sandboxed script has no way to run programs or load native
// code (os.execute, io.popen, package.loadlib, C modules, the debug library, binary chunks are
// gone) and reaches files only through PathPolicy: reads below the readable folders, writes
// below the writable ones. --unsafe lifts it all. scripting/README.md lists the details.

#include <filesystem>
#include <string>
#include <vector>

struct lua_State;

namespace graspkit::lua {

struct SandboxOptions {
  bool unsafe = false;                            // no sandbox at all
  std::vector<std::filesystem::path> allowRead;   // --allow-read
  std::vector<std::filesystem::path> allowWrite;  // --allow-write (readable too)
};

// Folder-based file permissions. A path is checked where the operating system would take it:
// relative to the current folder, `..` and every symbolic link followed (a link to a file not
// made yet too, as opening it for writing would create the target), so neither leads out.
class PathPolicy {
 public:
  PathPolicy() = default;  // unrestricted
  PathPolicy(std::vector<std::filesystem::path> readable,
             std::vector<std::filesystem::path> writable);
  static PathPolicy unrestricted() { return {}; }

  bool restricted() const { return restricted_; }
  bool mayRead(const std::filesystem::path& file) const;
  bool mayWrite(const std::filesystem::path& file) const;
  // Throw graspkit::Error naming the file, what was attempted and the allowed folders.
  void checkRead(const std::filesystem::path& file) const;
  void checkWrite(const std::filesystem::path& file) const;

  const std::vector<std::filesystem::path>& readable() const { return readable_; }
  const std::vector<std::filesystem::path>& writable() const { return writable_; }

 private:
  bool restricted_ = false;
  std::vector<std::filesystem::path> readable_;  // canonical; writable folders included
  std::vector<std::filesystem::path> writable_;  // canonical
};

// Replaces the standard library's dangerous parts in `L` (after luaL_openlibs): removes what
// runs programs or native code (and os.tmpname, io.tmpfile), routes io.open, io.lines, io.input,
// io.output, dofile, loadfile, os.remove, os.rename and require through `policy`, makes every
// loader text-only, and refuses __gc metamethods (finalizers run where no time limit reaches).
// A refusal is a Lua error naming the function, the file and the allowed folders. `policy` must
// outlive the state. require finds Lua modules in `module_folders` (package.path), never C ones.
void applySandbox(lua_State* L, const PathPolicy& policy,
                  const std::vector<std::filesystem::path>& module_folders);

}  // namespace graspkit::lua
