#pragma once
// What the exporters (URDF, MJCF, GraspIt! robot files) share: how a number is written, and what
// they do to a name that came from someone
// else's file before it goes into the XML they write or into a file name: a name may hold
// quotes, '<', '&', "--", control characters or a path ("../../x", "/abs/x").

#include <string>
#include <string_view>

namespace graspkit::io {

// `text` as XML character data or an attribute value: & < > " ' become entities, and control
// characters XML 1.0 cannot hold (all but tab, newline and carriage return) become '?'.
std::string xmlEscaped(std::string_view text);

// `text` inside an XML comment: "--" (which would end or break the comment) is split and a
// trailing '-' dropped; control characters become '?'.
std::string xmlCommentText(std::string_view text);

// A file stem made from `name`: letters, digits, '_', '-' and '.' kept, every other byte '_',
// leading dots dropped, at most 100 bytes; `fallback` when nothing is left. Joined to an output
// folder it always names a file directly inside that folder.
std::string fileStem(std::string_view name, std::string_view fallback);

// `value` with 17 significant digits, which reads back to the same double (URDF and MJCF).
std::string exactNumber(double value);

}  // namespace graspkit::io
