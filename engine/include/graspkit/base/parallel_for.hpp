#pragma once
// The engine's one way to run independent work on several threads: the planner's grasp
// finishing, grasp validation, and the planner plugins' restarts and samples all go through it.

#include <cstdint>
#include <functional>

namespace graspkit {

struct ParallelFor {
  std::int64_t begin = 0;
  std::int64_t end = 0;  // items are begin, begin+1, ..., end-1
  // Threads to use, the caller's included (it is worker 0); at most one per item, at least one.
  int threads = 1;
  // Cancellation: asked by each worker before it takes an item; once it returns false for a
  // worker, that worker takes no more. Empty: run every item. It must be safe to call from every
  // worker at once.
  std::function<bool(int worker)> keepGoing;
};

// Runs job(worker, index) once for every index of `run`, handed out in increasing order from
// one counter, so an item's worker depends on timing but an item is never run twice. Waits for
// every worker. When a job throws, the other workers take no new items, and the first error (by
// worker number) is rethrown here.
void parallelFor(const ParallelFor& run,
                 const std::function<void(int worker, std::int64_t index)>& job);

}  // namespace graspkit
