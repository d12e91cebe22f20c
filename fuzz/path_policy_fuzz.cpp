// libFuzzer target for the Lua sandbox's path policy: for any path (NUL bytes, `..`, symbolic
// links, very long names), mayRead and mayWrite answer without crashing, and a path they allow
// names a file below the allowed folder once resolved (the promise the sandbox rests on).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "graspkit/lua/sandbox.hpp"

namespace {

namespace fs = std::filesystem;

struct Tree {
  fs::path root, allowed;
  graspkit::lua::PathPolicy policy;
};

// root/allowed (the policy's one folder), root/outside, and a link allowed/out -> ../outside.
const Tree& tree() {
  static const Tree made = [] {
    std::string pattern = (fs::temp_directory_path() / "graspkit_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    Tree t;
    t.root = pattern;
    t.allowed = t.root / "allowed";
    fs::create_directories(t.allowed / "sub");
    fs::create_directories(t.root / "outside");
    fs::create_directory_symlink(t.root / "outside", t.allowed / "out");
    t.policy = graspkit::lua::PathPolicy({t.allowed}, {t.allowed});
    return t;
  }();
  return made;
}

// `file` resolved as far as the operating system lets it: a name too long to exist
// (ENAMETOOLONG) is resolved through its parent, whose symbolic links still count.
fs::path resolved(const fs::path& file) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(file, ec);
  if (!ec) return real;
  if (!file.has_relative_path() || file.parent_path() == file) return file.lexically_normal();
  return resolved(file.parent_path()) / file.filename();
}

bool below(const fs::path& file, const fs::path& folder) {
  const fs::path real = resolved(fs::absolute(file)).lexically_normal();
  const fs::path base = fs::canonical(folder);
  auto f = real.begin();
  for (auto b = base.begin(); b != base.end(); ++b, ++f)
    if (f == real.end() || *f != *b) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Tree& t = tree();
  // Relative inputs resolve against the allowed folder, as a script's would against its own.
  const fs::path file = t.allowed / std::string(reinterpret_cast<const char*>(data), size);
  const bool read = t.policy.mayRead(file);
  const bool write = t.policy.mayWrite(file);
  if (write && !read) std::abort();  // writable folders are readable
  if (read && file.native().find('\0') != std::string::npos) std::abort();
  if (read && !below(file, t.allowed)) std::abort();
  return 0;
}
