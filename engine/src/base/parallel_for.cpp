#include "graspkit/base/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace graspkit {

void parallelFor(const ParallelFor& run,
                 const std::function<void(int worker, std::int64_t index)>& job) {
  if (run.end <= run.begin) return;
  const std::int64_t items = run.end - run.begin;
  const int workers = static_cast<int>(std::clamp<std::int64_t>(run.threads, 1, items));
  std::atomic<std::int64_t> next{run.begin};
  std::atomic<bool> failed{false};
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  auto work = [&](int worker) {
    try {
      while (!failed && (!run.keepGoing || run.keepGoing(worker))) {
        const std::int64_t index = next++;
        if (index >= run.end) break;
        job(worker, index);
      }
    } catch (...) {
      errors[static_cast<std::size_t>(worker)] = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(workers - 1));
  for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace graspkit
