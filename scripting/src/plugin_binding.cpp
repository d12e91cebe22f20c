#include "module.hpp"

namespace graspkit::lua {

void openPluginFunctions(lua_State*) {}

}  // namespace graspkit::lua
