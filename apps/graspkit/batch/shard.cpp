#include "batch/shard.hpp"

#include <charconv>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit::cli {

// A whole number from 1 to kMaxShards written as one, or nullopt.
namespace {

std::optional<int> shardNumber(std::string_view text) {
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value < 0 ||
      value > kMaxShards)
    return std::nullopt;
  return static_cast<int>(value);
}

}  // namespace

Shard shardOf(const std::string& text) {
  if (!text.empty()) {
    const auto slash = text.find('/');
    const auto k = shardNumber(std::string_view(text).substr(0, slash));
    const auto n = slash == std::string::npos
                       ? std::nullopt
                       : shardNumber(std::string_view(text).substr(slash + 1));
    if (!k || !n || *k < 1 || *k > *n)
      throw Error(fmt::format("--shard: '{}' is not K/N with 1 <= K <= N <= {}", text, kMaxShards));
    return {*k - 1, *n};
  }
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  if (!id || !count) return {};
  const auto task = shardNumber(id);
  const auto tasks = shardNumber(count);
  const auto first = min ? shardNumber(min) : std::optional<int>(0);
  if (!task || !tasks || !first || *tasks < 1 || *task < *first || *task - *first >= *tasks)
    throw Error(
        fmt::format("SLURM_ARRAY_TASK_ID={} of SLURM_ARRAY_TASK_COUNT={} (first {}) is not "
                    "a task of the array",
                    id, count, min ? min : "0"));
  return {*task - *first, *tasks};
}

}  // namespace graspkit::cli
