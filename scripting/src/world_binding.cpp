#include "module.hpp"

namespace graspkit::lua {

void openWorldFunctions(lua_State*) {}

}  // namespace graspkit::lua
