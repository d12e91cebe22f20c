#include "hand_state_file.hpp"
#include "graspkit/base/input_file.hpp"

#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"

namespace graspkit::list {

namespace {

using nlohmann::json;

// The finite numbers of `entry[key]`: exactly `size` of them, or any non-zero count when
// size is 0. Returns the problem, empty when there is none.
std::string numbers(const json& entry, const char* key, std::size_t size,
                    std::vector<double>& out) {
  if (!entry.contains(key)) return fmt::format("no \"{}\"", key);
  const json& value = entry.at(key);
  if (!value.is_array() || (size != 0 && value.size() != size) || (size == 0 && value.empty()))
    return size != 0 ? fmt::format("\"{}\" is not an array of {} numbers", key, size)
                     : fmt::format("\"{}\" is not a non-empty array of numbers", key);
  out.clear();
  for (const json& x : value) {
    if (!x.is_number() || !std::isfinite(x.get<double>()))
      return fmt::format("\"{}\" holds {}, not a finite number", key, x.dump());
    out.push_back(x.get<double>());
  }
  return {};
}

HandState handState(const json& entry, std::string& problem) {
  HandState state;
  if (!entry.is_object()) {
    problem = "not an object";
    return state;
  }
  std::vector<double> t, q;
  problem = numbers(entry, "translation", 3, t);
  if (problem.empty()) problem = numbers(entry, "quaternion", 4, q);
  if (problem.empty()) problem = numbers(entry, "dofs", 0, state.dofs);
  if (!problem.empty()) return state;
  const Quaternion rotation(q[0], q[1], q[2], q[3]);
  if (rotation.norm() < 1e-9) {
    problem = "\"quaternion\" is zero";
    return state;
  }
  state.pose = makeTransform(Vector3(t[0], t[1], t[2]), rotation.normalized());
  return state;
}

}  // namespace

std::vector<HandState> readHandStates(const std::filesystem::path& file) {
  const std::string text = readInputFile(file);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(fmt::format("list: {}: not JSON: {}", file.string(), e.what()));
  }
  const json* entries = &document;
  if (document.is_object() && document.contains("grasps")) entries = &document.at("grasps");
  if (!entries->is_array())
    throw Error(fmt::format(
        "list: {}: expected an array of hand states (or an object with a \"grasps\" array)",
        file.string()));
  std::vector<HandState> states;
  for (std::size_t i = 0; i < entries->size(); ++i) {
    std::string problem;
    states.push_back(handState(entries->at(i), problem));
    if (!problem.empty())
      throw Error(fmt::format("list: {}: entry {}: {}", file.string(), i, problem));
  }
  return states;
}

}  // namespace graspkit::list
