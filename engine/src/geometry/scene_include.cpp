#include "geometry/scene_include.hpp"

#include <fmt/format.h>

#include "geometry/mesh_readers.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"

namespace graspkit::detail {
namespace {

namespace fs = std::filesystem;

// Whether `file` lies in `folder` or below it (both already resolved).
bool isWithin(const fs::path& file, const fs::path& folder) {
  auto f = file.begin();
  for (auto d = folder.begin(); d != folder.end(); ++d, ++f)
    if (f == file.end() || *f != *d) return false;
  return true;
}

}  // namespace

std::optional<fs::path> resolveInclude(const std::string& name,
                                       const std::vector<fs::path>& folders, const fs::path& root,
                                       const std::string& including, int line) {
  const SourceLocation where = locationIn(including, line);
  if (name.empty()) throw Error(where, "a File node with no name");
  const fs::path relative(name);
  if (relative.is_absolute()) {
    throw Error(where, fmt::format("File node names the absolute path '{}'; only names relative "
                                   "to the including file are read",
                                   name));
  }
  std::error_code ec;
  const fs::path real_root = fs::weakly_canonical(root, ec);
  for (const fs::path& folder : folders) {
    const fs::path candidate = folder / relative;
    if (!inputFileFound(candidate)) continue;
    const fs::path real = fs::weakly_canonical(candidate, ec);
    // Where it leads is not named: it may lie where a sandboxed script may not look.
    if (ec || !isWithin(real, real_root)) {
      throw Error(where, fmt::format("File node names '{}', which leads outside the model's "
                                     "folder {}",
                                     name, real_root.string()));
    }
    return candidate;
  }
  return std::nullopt;
}

}  // namespace graspkit::detail
