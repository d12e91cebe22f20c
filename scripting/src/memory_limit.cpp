#include "memory_limit.hpp"

#include <cstdlib>

namespace graspkit::lua {

void* limitedAllocate(void* ud, void* block, std::size_t oldSize, std::size_t newSize) {
  auto& memory = *static_cast<LuaMemory*>(ud);
  // When block is null, oldSize encodes the kind of object being made, not a size.
  const std::size_t held = block != nullptr ? oldSize : 0;
  if (newSize == 0) {
    std::free(block);
    memory.used -= held;
    return nullptr;
  }
  if (newSize > held && memory.limit != 0 && memory.used - held + newSize > memory.limit) {
    memory.refused = true;
    return nullptr;
  }
  void* grown = std::realloc(block, newSize);
  if (grown == nullptr) return nullptr;
  memory.used = memory.used - held + newSize;
  return grown;
}

}  // namespace graspkit::lua
