// The contact search's filter of exact repeats, against a second method (an ordered set of the
// points' bit patterns), and the claim it rests on: removeDuplicates gives the same survivors,
// in the same order, whether or not the exact repeats are there.

#include "collision/distinct_point_pairs.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "collision/contact_compaction.hpp"

namespace graspkit::collision {
namespace {

using Bits = std::array<std::uint64_t, 6>;

Bits bitsOf(const RawContact& c) {
  Bits bits;
  for (int i = 0; i < 3; ++i) {
    bits[i] = std::bit_cast<std::uint64_t>(c.onFirst[i]);
    bits[3 + i] = std::bit_cast<std::uint64_t>(c.onSecond[i]);
  }
  return bits;
}

// Contacts drawn from a pool of `pool` point pairs on a 0.01 mm grid, so that many repeat
// exactly and many lie within a duplicate distance of others; each draw has its own face normal,
// which tells a copy from its original.
std::vector<RawContact> drawContacts(std::size_t count, std::size_t pool, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> grid(0, 300);
  std::vector<RawContact> points(pool);
  for (RawContact& c : points) {
    c.onFirst = Vector3(grid(random), grid(random), grid(random)) * 0.01;
    c.onSecond = c.onFirst + Vector3(grid(random), grid(random), grid(random)) * 1e-4;
  }
  std::uniform_int_distribution<std::size_t> pick(0, pool - 1);
  std::normal_distribution<double> normal;
  std::vector<RawContact> drawn;
  for (std::size_t i = 0; i < count; ++i) {
    RawContact c = points[pick(random)];
    c.intoFirst = Vector3(normal(random), normal(random), normal(random)).normalized();
    c.rank = c.distanceSq();
    drawn.push_back(c);
  }
  return drawn;
}

std::vector<RawContact> admitted(DistinctPointPairs& distinct, const std::vector<RawContact>& in,
                                 std::vector<RawContact> out = {}) {
  distinct.start(out);
  for (const RawContact& c : in)
    if (distinct.admit(out, c)) out.push_back(c);
  return out;
}

void expectSameContacts(const std::vector<RawContact>& a, const std::vector<RawContact>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(bitsOf(a[i]), bitsOf(b[i])) << "contact " << i;
    EXPECT_EQ(a[i].intoFirst, b[i].intoFirst) << "contact " << i;
  }
}

TEST(DistinctPointPairs, KeepsTheFirstOfEachExactRepeatAsASetDoes) {
  DistinctPointPairs distinct;
  // Several searches on one filter: its table grows past its first size, then starts small.
  for (const auto& [count, pool] :
       {std::pair{20000, 3000}, std::pair{50, 10}, std::pair{5000, 5000}, std::pair{1, 1}}) {
    const std::vector<RawContact> drawn = drawContacts(count, pool, count + pool);
    std::set<Bits> seen;
    std::vector<RawContact> expected;
    for (const RawContact& c : drawn)
      if (seen.insert(bitsOf(c)).second) expected.push_back(c);
    const std::vector<RawContact> kept = admitted(distinct, drawn);
    expectSameContacts(kept, expected);
    if (count > 1) EXPECT_LT(kept.size(), drawn.size()) << "the draws must repeat";
  }
}

TEST(DistinctPointPairs, ComparesBitsAndForgetsEarlierSearches) {
  DistinctPointPairs distinct;
  RawContact zero;
  zero.onFirst = zero.onSecond = Vector3::Zero();
  RawContact negative_zero = zero;
  negative_zero.onFirst.x() = -0.0;  // equal as a number, another point pair as bits
  RawContact not_a_number = zero;
  not_a_number.onSecond.y() = std::numeric_limits<double>::quiet_NaN();
  const std::vector<RawContact> in = {zero, negative_zero, not_a_number, not_a_number, zero};
  // NaN points equal nothing, not even themselves, as in removeDuplicates: both copies stay.
  const std::vector<RawContact> kept = admitted(distinct, in);
  ASSERT_EQ(kept.size(), 4u);
  EXPECT_TRUE(std::signbit(kept[1].onFirst.x()));
  EXPECT_TRUE(std::isnan(kept[2].onSecond.y()) && std::isnan(kept[3].onSecond.y()));
  // A search that appends to earlier contacts compares only with its own.
  const std::vector<RawContact> appended = admitted(distinct, {zero, zero}, {zero});
  EXPECT_EQ(appended.size(), 2u);
}

TEST(DistinctPointPairs, RemoveDuplicatesKeepsTheSameSurvivorsWithoutExactRepeats) {
  DistinctPointPairs distinct;
  for (const double duplicate_distance : {0.0, 0.005, 0.02, 0.1}) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const std::vector<RawContact> drawn = drawContacts(3000, 400 * seed, seed);
      std::vector<RawContact> all = drawn;
      std::vector<RawContact> distinct_only = admitted(distinct, drawn);
      ASSERT_LT(distinct_only.size(), all.size());
      removeDuplicates(all, duplicate_distance);
      removeDuplicates(distinct_only, duplicate_distance);
      SCOPED_TRACE(::testing::Message() << "distance " << duplicate_distance << ", seed " << seed);
      expectSameContacts(distinct_only, all);
      EXPECT_GT(all.size(), 1u);
    }
  }
}

}  // namespace
}  // namespace graspkit::collision
