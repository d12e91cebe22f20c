#pragma once
// The objects of graspkit batch: the files --objects names, and a name for each.

#include <filesystem>
#include <string>
#include <vector>

#include "graspkit/base/error.hpp"

namespace graspkit::cli {

// Throws graspkit::Error at `where` when `text` is not UTF-8: object names and paths go into the
// manifest (JSON) and the datasets (HDF5 UTF-8 strings).
void requireUtf8(const std::string& text, const SourceLocation& where, const char* what);

// Every .xml body file of a folder (objects.txt's order when it has one), or the lines of a list
// file (# starts a comment; paths relative to the list's folder).
std::vector<std::filesystem::path> objectFiles(const std::filesystem::path& source);

// The files' stems, made unique (mug, mug_2, ...).
std::vector<std::string> objectNames(const std::vector<std::filesystem::path>& files);

}  // namespace graspkit::cli
