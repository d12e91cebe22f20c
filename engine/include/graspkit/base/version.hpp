#pragma once
// The engine's version, as saved results record it.

namespace graspkit {

const char* engineVersion();  // "0.1.0"

}  // namespace graspkit
