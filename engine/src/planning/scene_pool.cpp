#include "graspkit/planning/scene_pool.hpp"

#include <algorithm>

namespace graspkit {

ScenePool::ScenePool(const PlanningRequest& request, std::shared_ptr<const SearchSpace> space)
    : request_(request),
      space_(std::move(space)),
      capacity_(request.customEnergy ? 1 : std::max(request.threads, 1)) {
  grow(1);
}

PlanningScene& ScenePool::scene(int worker) {
  return *scenes_.at(static_cast<std::size_t>(worker));
}

const std::shared_ptr<PlanningScene>& ScenePool::sharedScene(int worker) {
  return scenes_.at(static_cast<std::size_t>(worker));
}

SearchEnergy& ScenePool::energy(int worker) {
  return *energies_.at(static_cast<std::size_t>(worker));
}

void ScenePool::grow(int count) {
  while (size() < count) {
    scenes_.push_back(makePlanningScene(request_, space_));
    energies_.push_back(makeSearchEnergy(request_));
  }
}

void ScenePool::run(std::int64_t begin, std::int64_t end,
                    const std::function<void(int worker, std::int64_t index)>& job,
                    const std::function<bool(int worker)>& keepGoing) {
  if (end <= begin) return;
  const int workers = static_cast<int>(std::min<std::int64_t>(capacity_, end - begin));
  grow(workers);  // on this thread: clones are made before any worker starts
  parallelFor({.begin = begin, .end = end, .threads = workers, .keepGoing = keepGoing}, job);
}

}  // namespace graspkit
