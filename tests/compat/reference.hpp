#pragma once
// Access to GraspIt!'s own figures (../shared/reference/graspit-figures.json) for the
// compatibility tests.

#include <fstream>

#include <nlohmann/json.hpp>

#include "graspkit/math/transform.hpp"
#include "test_paths.hpp"

namespace graspkit::test {

inline const nlohmann::json& referenceJson() {
  static const nlohmann::json json = [] {
    std::ifstream in(*referenceFigures());
    return nlohmann::json::parse(in);
  }();
  return json;
}

inline Vector3 jsonVector3(const nlohmann::json& j) {
  return Vector3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

// A reference pose {"t_mm": [..], "q_wxyz": [..]}.
inline Transform jsonPose(const nlohmann::json& j) {
  const auto& q = j.at("q_wxyz");
  return makeTransform(jsonVector3(j.at("t_mm")),
                       Quaternion(q.at(0).get<double>(), q.at(1).get<double>(),
                                  q.at(2).get<double>(), q.at(3).get<double>()));
}

}  // namespace graspkit::test
