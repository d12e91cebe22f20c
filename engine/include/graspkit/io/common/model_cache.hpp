#pragma once
// Files already loaded, so a body used by several links or worlds is read and meshed once.
// Thread-safe; entries are immutable.

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

#include "graspkit/model/body.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

class ModelCache {
 public:
  std::shared_ptr<const BodyModel> body(
      const std::filesystem::path& file,
      const std::function<std::shared_ptr<const BodyModel>()>& load);
  std::shared_ptr<const RobotModel> robot(
      const std::filesystem::path& file,
      const std::function<std::shared_ptr<const RobotModel>()>& load);

 private:
  std::mutex mutex_;
  std::map<std::filesystem::path, std::shared_ptr<const BodyModel>> bodies_;
  std::map<std::filesystem::path, std::shared_ptr<const RobotModel>> robots_;
};

}  // namespace graspkit
