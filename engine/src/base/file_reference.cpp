#include "graspkit/base/file_reference.hpp"

#include <system_error>

namespace graspkit {

namespace fs = std::filesystem;

namespace {

// `path` made absolute against the working folder, its symbolic links resolved as far as it
// exists (weakly_canonical); an error (a loop of links) leaves it absolute and lexically normal.
fs::path physical(const fs::path& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path.empty() ? fs::path(".") : path, ec);
  if (ec) return path.lexically_normal();
  fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

}  // namespace

std::string fileReference(const fs::path& target, const fs::path& folder) {
  const fs::path to = physical(target);
  const fs::path from = physical(folder);
  const fs::path to_inside = to.relative_path();
  const fs::path from_inside = from.relative_path();
  // A shared first folder below the root (/work/a and /work/b): relative. Only the root in
  // common (/tmp/out and /work/models): absolute, which a move of either side keeps valid.
  if (to.root_path() == from.root_path() && !to_inside.empty() && !from_inside.empty() &&
      *to_inside.begin() == *from_inside.begin()) {
    const fs::path relative = to.lexically_relative(from);
    if (!relative.empty() && relative != ".") return relative.generic_string();
  }
  return to.generic_string();
}

bool isFileRelative(std::string_view name) {
  const fs::path path(name);
  if (path.empty() || path.is_absolute()) return false;
  const fs::path first = *path.begin();
  return first == "." || first == "..";
}

}  // namespace graspkit
