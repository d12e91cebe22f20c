#include "module.hpp"

namespace graspkit::lua {

void registerGraspClass(lua_State*) {}

}  // namespace graspkit::lua
