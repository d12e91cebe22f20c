#pragma once
// Internal: a search's raw contacts without their exact repeats. A vertex near a face is found
// once from every triangle around the vertex, and an edge near an edge from both triangles on
// each side: two dense meshes face to face gave each point pair about 8 times (2.1 million raw
// contacts, 256 thousand distinct). Dropping a later copy whose two points are bit for bit an
// earlier one's cannot change which contacts survive removeDuplicates: the copy ranks equal to
// its original, comes after it, and any survivor near one is as near the other.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/contact_compaction.hpp"
#include "collision/working_memory.hpp"

namespace graspkit::collision {

class DistinctPointPairs {
 public:
  // Begins a search whose contacts are appended to `contacts` from its present end.
  void start(const std::vector<RawContact>& contacts) {
    base_ = contacts.size();
    count_ = 0;
    resetSlots(kFirstSlots);
  }

  // Whether `candidate` is new to this search, in which case it is remembered as the next
  // element of `contacts` and the caller appends it. Points that are not finite never compare
  // equal (as in removeDuplicates), so they are always new and never remembered.
  bool admit(const std::vector<RawContact>& contacts, const RawContact& candidate) {
    if (!candidate.onFirst.allFinite() || !candidate.onSecond.allFinite()) return true;
    if (2 * (count_ + 1) > slots_size_) grow(contacts);
    std::size_t slot = hash(candidate) & (slots_size_ - 1);
    while (slots_[slot] != 0) {
      if (samePoints(contacts[slots_[slot] - 1], candidate)) return false;
      slot = (slot + 1) & (slots_size_ - 1);
    }
    slots_[slot] = static_cast<std::uint32_t>(contacts.size() + 1);
    ++count_;
    return true;
  }

  // Frees the table after an unusually large search (see working_memory.hpp).
  void keepOrReleaseMemory() { keepOrRelease(slots_); }

 private:
  static constexpr std::size_t kFirstSlots = 256;

  static bool samePoints(const RawContact& a, const RawContact& b) {
    for (int i = 0; i < 3; ++i) {
      if (std::bit_cast<std::uint64_t>(a.onFirst[i]) != std::bit_cast<std::uint64_t>(b.onFirst[i]))
        return false;
      if (std::bit_cast<std::uint64_t>(a.onSecond[i]) !=
          std::bit_cast<std::uint64_t>(b.onSecond[i]))
        return false;
    }
    return true;
  }

  static std::uint64_t hash(const RawContact& c) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    auto mix = [&h](double value) {
      h = (h ^ std::bit_cast<std::uint64_t>(value)) * 0xff51afd7ed558ccdULL;
      h ^= h >> 29;
    };
    for (int i = 0; i < 3; ++i) mix(c.onFirst[i]);
    for (int i = 0; i < 3; ++i) mix(c.onSecond[i]);
    return h;
  }

  // Only the first `size` slots are in use; the vector keeps what a larger search grew.
  void resetSlots(std::size_t size) {
    if (slots_.size() < size) slots_.resize(size);
    std::fill(slots_.begin(), slots_.begin() + static_cast<std::ptrdiff_t>(size), 0u);
    slots_size_ = size;
  }

  // Doubles the table and enters again every contact remembered so far: they are exactly
  // contacts[base_, end), as nothing else is appended between admissions.
  void grow(const std::vector<RawContact>& contacts) {
    resetSlots(2 * slots_size_);
    for (std::size_t index = base_; index < contacts.size(); ++index) {
      const RawContact& c = contacts[index];
      if (!c.onFirst.allFinite() || !c.onSecond.allFinite()) continue;
      std::size_t slot = hash(c) & (slots_size_ - 1);
      while (slots_[slot] != 0) slot = (slot + 1) & (slots_size_ - 1);
      slots_[slot] = static_cast<std::uint32_t>(index + 1);
    }
  }

  std::vector<std::uint32_t> slots_;  // 0: empty; else the contact's index + 1
  std::size_t slots_size_ = 0;
  std::size_t count_ = 0;
  std::size_t base_ = 0;
};

}  // namespace graspkit::collision
