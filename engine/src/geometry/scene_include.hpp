#pragma once
// Inventor File nodes (Coin's SoFile): geometry split over several files. Coin resolves a File
// node's name against the working folder, the including file's folder and those of the files
// around it, and reads whatever it finds there, itself included (and then overflows its stack).
// graspkit reads includes itself, under rules that keep a model inside its own folder:
// - only relative names, resolved against the including file's folder, then the folders of the
//   files that include it, innermost first (never the working folder);
// - the file found must lie inside the model root (the outermost geometry file's folder) once
//   `..` and symbolic links are resolved; it is read through readInputFile (regular files only,
//   the size bound, the read guard of a sandboxed script);
// - each included file is parsed on its own, with its own header (an Inventor V2.1 file may
//   include a VRML 1.0 one); a file that includes itself, directly or not, is an error, and so is
//   nesting deeper than kMaxIncludeDepth or more than kMaxIncludedBytes of text in all;
// - a name found in none of the folders is a warning, and the node is skipped, as in Coin.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace graspkit::detail {

inline constexpr int kMaxIncludeDepth = 16;
inline constexpr std::size_t kMaxIncludedBytes = std::size_t{1} << 30;

// A File node as the text check found it.
struct SceneInclude {
  std::string name;    // the name field, as written
  int line = 0;        // where the node is, in the including file
  std::string marker;  // the placeholder's Info string that stands for it in the parsed scene
};

// The file `name` names, looked for in `folders` (innermost first): the first that exists.
// nullopt when none holds it (the caller warns). Throws graspkit::Error, located at `line` of
// `including`, for an absolute name or one that resolves outside `root`.
std::optional<std::filesystem::path> resolveInclude(
    const std::string& name, const std::vector<std::filesystem::path>& folders,
    const std::filesystem::path& root, const std::string& including, int line);

}  // namespace graspkit::detail
