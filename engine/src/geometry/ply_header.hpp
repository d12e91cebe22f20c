#pragma once
// Internal: a check of a PLY file's header before assimp reads it. assimp trusts the element
// counts and property types a header declares and reserves memory or reads past the end on
// their word; a 120-byte file can ask for gigabytes. The check refuses a header that does not
// parse, names an unknown type, or promises more data than the file holds.

#include <string_view>

#include "graspkit/base/error.hpp"

namespace graspkit::detail {

// Throws graspkit::Error located at `where` (with the header line when known).
void checkPlyHeader(std::string_view bytes, const SourceLocation& where);

}  // namespace graspkit::detail
