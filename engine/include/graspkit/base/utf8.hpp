#pragma once
// UTF-8 validity. XML files, names and object lists are UTF-8 text; a byte sequence that is not
// is refused where it enters, so that a name can always be written back (JSON, HDF5 strings,
// XML) and printed.

#include <cstddef>
#include <optional>
#include <string_view>

namespace graspkit {

// The offset of the first byte that does not begin a well-formed UTF-8 sequence (overlong
// forms, surrogates and code points past U+10FFFF are ill-formed), or nullopt when all are.
std::optional<std::size_t> firstInvalidUtf8(std::string_view text);

// The length of the well-formed UTF-8 sequence at the start of `text`, or 0 when none is there.
std::size_t utf8SequenceLength(std::string_view text);

}  // namespace graspkit
