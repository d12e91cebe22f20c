// parallelFor (base/parallel_for.hpp) and the enum name tables (base/enum_names.hpp).

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/parallel_for.hpp"
#include "graspkit/grasp/wrench_space.hpp"
#include "graspkit/planning/search_space.hpp"

namespace graspkit {
namespace {

TEST(ParallelFor, RunsEveryItemOnceWhateverTheThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<std::atomic<int>> runs(101);
    std::mutex mutex;
    std::set<int> workers;
    parallelFor({.begin = 7, .end = 108, .threads = threads}, [&](int worker, std::int64_t i) {
      runs[static_cast<std::size_t>(i - 7)]++;
      std::lock_guard lock(mutex);
      workers.insert(worker);
    });
    for (const auto& count : runs) EXPECT_EQ(count.load(), 1) << threads << " threads";
    // Worker numbers are 0 .. threads-1 (the caller is 0), never more than asked.
    EXPECT_LE(static_cast<int>(workers.size()), threads);
    for (int w : workers) EXPECT_TRUE(w >= 0 && w < threads);
  }
}

TEST(ParallelFor, NoItemsAndMoreThreadsThanItems) {
  int calls = 0;
  parallelFor({.begin = 5, .end = 5, .threads = 4}, [&](int, std::int64_t) { ++calls; });
  parallelFor({.begin = 5, .end = 3, .threads = 4}, [&](int, std::int64_t) { ++calls; });
  EXPECT_EQ(calls, 0);
  std::atomic<int> maxWorker{-1};
  parallelFor({.begin = 0, .end = 2, .threads = 16}, [&](int worker, std::int64_t) {
    int seen = maxWorker.load();
    while (worker > seen && !maxWorker.compare_exchange_weak(seen, worker)) {
    }
  });
  EXPECT_LE(maxWorker.load(), 1);  // one worker per item at most
}

TEST(ParallelFor, KeepGoingStopsTakingItems) {
  std::atomic<int> done{0};
  parallelFor(
      {.begin = 0, .end = 1000, .threads = 2, .keepGoing = [&](int) { return done.load() < 10; }},
      [&](int, std::int64_t) { ++done; });
  // Each worker may finish the item it took before it saw the limit.
  EXPECT_GE(done.load(), 10);
  EXPECT_LE(done.load(), 11);
}

TEST(ParallelFor, AnErrorIsRethrownAndStopsTheOthers) {
  std::atomic<int> done{0};
  // The items after the failing one take a while, so that a worker left to run alone (the
  // failing one descheduled before it could raise the stop, as on a loaded 2-core machine under
  // a sanitizer) cannot finish them all before the stop: without a stop this takes seconds.
  EXPECT_THROW(parallelFor({.begin = 0, .end = 100000, .threads = 2},
                           [&](int, std::int64_t i) {
                             if (i == 3) throw Error("item 3 failed");
                             if (i > 3) std::this_thread::sleep_for(std::chrono::microseconds(50));
                             ++done;
                           }),
               Error);
  EXPECT_LT(done.load(), 100000 - 1);
}

TEST(EnumNames, NamesAliasesAndTheListInErrors) {
  EXPECT_EQ(nameOf(PositionSpace::AxisAngle), "axis-angle");
  EXPECT_EQ(valueNamed<PositionSpace>("axis-angle"), PositionSpace::AxisAngle);
  EXPECT_EQ(valueNamed<PositionSpace>("SPACE_AXIS_ANGLE"), PositionSpace::AxisAngle);  // GraspIt!'s
  EXPECT_FALSE(valueNamed<PositionSpace>("Axis-Angle").has_value());  // exact names only
  EXPECT_EQ(namesOf<PositionSpace>(), "complete, axis-angle, ellipsoid or approach");
  EXPECT_EQ(namesOf<WrenchSpaceType>(), "L1 or Linf");  // the alias LInfinity is not listed
  EXPECT_EQ(valueNamed<WrenchSpaceType>("LInfinity"), WrenchSpaceType::LInfinity);
  try {
    parseNamed<PostureSpace>("pose", "posture space");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "unknown posture space 'pose'; expected eigen or dof");
  }
  // A value outside the table (a bad cast) is named, not undefined.
  EXPECT_EQ(nameOf(static_cast<PostureSpace>(99)), "unknown");
}

}  // namespace
}  // namespace graspkit
