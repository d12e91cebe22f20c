#include "module.hpp"

namespace graspkit::lua {

void registerRobotClass(lua_State*) {}

}  // namespace graspkit::lua
