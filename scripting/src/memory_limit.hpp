#pragma once
// The Lua heap's allocator, with a limit: a script that builds strings or tables without end
// gets Lua's "not enough memory" error instead of taking the machine's memory.

#include <cstddef>

namespace graspkit::lua {

struct LuaMemory {
  std::size_t used = 0;   // bytes the Lua state holds
  std::size_t limit = 0;  // 0: none
  bool refused = false;   // an allocation was refused for the limit
};

// A lua_Alloc; `ud` is a LuaMemory. Shrinking and freeing always succeed, as Lua requires.
void* limitedAllocate(void* ud, void* block, std::size_t oldSize, std::size_t newSize);

}  // namespace graspkit::lua
