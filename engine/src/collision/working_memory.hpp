#pragma once
// Internal: the rule for working memory a contact search keeps between calls. A simulation step
// searches the same pairs again and again, and growing the same large vectors afresh each time
// cost more in page faults than the search itself; but one unusual search (two dense meshes face
// to face) must not pin its peak for the life of the thread.

#include <cstddef>
#include <vector>

namespace graspkit::collision {

// Bytes a thread may keep in one working vector between searches (about 64 MB).
inline constexpr std::size_t kKeptWorkingBytes = std::size_t{64} << 20;

// Frees `memory` when its capacity exceeds kKeptWorkingBytes; otherwise it is kept for reuse.
template <class T>
void keepOrRelease(std::vector<T>& memory) {
  if (memory.capacity() * sizeof(T) > kKeptWorkingBytes) std::vector<T>().swap(memory);
}

}  // namespace graspkit::collision
