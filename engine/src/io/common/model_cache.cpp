#include "graspkit/io/common/model_cache.hpp"

namespace graspkit {
namespace {

std::filesystem::path key(const std::filesystem::path& file) {
  std::error_code ec;
  auto canonical = std::filesystem::weakly_canonical(file, ec);
  return ec ? file.lexically_normal() : canonical;
}

// Loads outside the lock (loads can be slow and may recurse into the cache), then keeps the
// first entry stored for the key.
template <typename Model, typename Map, typename Load>
std::shared_ptr<const Model> lookup(std::mutex& mutex, Map& map, const std::filesystem::path& file,
                                    const Load& load) {
  const auto k = key(file);
  {
    std::lock_guard lock(mutex);
    if (auto it = map.find(k); it != map.end()) return it->second;
  }
  auto loaded = load();
  std::lock_guard lock(mutex);
  return map.emplace(k, std::move(loaded)).first->second;
}

}  // namespace

std::shared_ptr<const BodyModel> ModelCache::body(
    const std::filesystem::path& file,
    const std::function<std::shared_ptr<const BodyModel>()>& load) {
  return lookup<BodyModel>(mutex_, bodies_, file, load);
}

std::shared_ptr<const RobotModel> ModelCache::robot(
    const std::filesystem::path& file,
    const std::function<std::shared_ptr<const RobotModel>()>& load) {
  return lookup<RobotModel>(mutex_, robots_, file, load);
}

}  // namespace graspkit
