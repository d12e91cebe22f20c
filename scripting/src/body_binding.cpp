#include "module.hpp"

namespace graspkit::lua {

void registerBodyClass(lua_State*) {}

}  // namespace graspkit::lua
