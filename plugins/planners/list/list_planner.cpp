#include "list_planner.hpp"

#include <optional>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/scene_pool.hpp"
#include "hand_state_file.hpp"
#include "sampling.hpp"

namespace graspkit::list {

namespace {

// GraspIt!'s list planner only keeps states below this energy.
constexpr double kEntryBar = 1.0e5;

std::vector<std::vector<double>> requestStates(const PlanningRequest& request,
                                               const SearchSpace& space) {
  std::vector<std::vector<double>> values;
  for (std::size_t i = 0; i < request.states.size(); ++i) {
    const auto& v = request.states[i].values;
    if (static_cast<int>(v.size()) != space.size())
      throw Error(fmt::format("list: states[{}] has {} values; the {}/{} space has {}", i, v.size(),
                              nameOf(space.positionSpace()), nameOf(space.postureSpace()),
                              space.size()));
    values.push_back(v);
  }
  return values;
}

// Each entry of `file` encoded in the search space; an entry the space cannot represent
// exactly is an error, since evaluating a different state than the file names would mislead.
std::vector<std::vector<double>> fileStates(const std::string& file, const SearchSpace& space,
                                            int dofCount) {
  std::vector<std::vector<double>> values;
  const std::vector<HandState> states = readHandStates(file);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const HandState& s = states[i];
    if (static_cast<int>(s.dofs.size()) != dofCount)
      throw Error(fmt::format("list: {}: entry {}: {} DOF values for a hand with {}", file, i,
                              s.dofs.size(), dofCount));
    if (space.positionSpace() == PositionSpace::Ellipsoid)
      throw Error(
          fmt::format("list: {}: the ellipsoid space cannot hold given hand poses; use complete or "
                      "axis-angle",
                      file));
    std::optional<std::vector<double>> encoded = planners::encodeExactly(space, s.pose, s.dofs);
    if (!encoded)
      throw Error(fmt::format(
          "list: {}: entry {}: the {}/{} search space cannot represent this hand state (a pose "
          "outside its ranges, DOFs outside their limits or, for eigen postures, off the "
          "eigengrasp subspace); try --space complete or --posture dof",
          file, i, nameOf(space.positionSpace()), nameOf(space.postureSpace())));
    values.push_back(std::move(*encoded));
  }
  return values;
}

class ListPlanner final : public Planner {
 public:
  explicit ListPlanner(const PlanningRequest& request)
      : space_(makeSearchSpace(request)), ranked_(request.bestListSize) {
    if (request.threads < 1)
      throw Error(fmt::format("list: {} threads is not valid", request.threads));
    if (request.bestListSize < 1)
      throw Error(fmt::format("list: a best list of {} is not valid", request.bestListSize));
    inputs_ = requestStates(request, *space_);
    for (const auto& [key, value] : request.options) {
      if (key != "file") throw Error(fmt::format("list: unknown option '{}'; known: file", key));
      const int dofCount =
          static_cast<int>(request.world->robot(request.robot).model().dofs.size());
      for (auto& v : fileStates(value, *space_, dofCount)) inputs_.push_back(std::move(v));
    }
    if (inputs_.empty())
      throw Error(
          "list: no hand states to evaluate: give the request's states or the option "
          "file=FILE");
    workers_ = std::make_unique<ScenePool>(request, space_);
  }

  void step(std::int64_t steps) override {
    const auto total = static_cast<std::int64_t>(inputs_.size());
    // A step of fewer states than workers would leave workers idle: take at least one each.
    const std::int64_t end =
        std::min(total, next_ + std::max<std::int64_t>(steps, workers_->capacity()));
    std::vector<std::optional<double>> energies(static_cast<std::size_t>(end - next_));
    workers_->run(next_, end, [&](int w, std::int64_t i) {
      energies[static_cast<std::size_t>(i - next_)] = evaluateState(
          workers_->scene(w), workers_->energy(w), inputs_[static_cast<std::size_t>(i)]);
    });
    for (std::int64_t i = next_; i < end; ++i) {
      const std::optional<double>& e = energies[static_cast<std::size_t>(i - next_)];
      if (e && *e < kEntryBar) ranked_.offer({inputs_[static_cast<std::size_t>(i)], *e});
    }
    next_ = end;
  }

  bool done() const override { return next_ >= static_cast<std::int64_t>(inputs_.size()); }
  std::int64_t stepsDone() const override { return next_; }

  std::vector<PlannedGrasp> best() const override {
    std::vector<PlannedGrasp> grasps;
    for (const SearchState& s : ranked_.states()) grasps.push_back(plannedGrasp(*space_, s));
    return grasps;
  }

 private:
  std::shared_ptr<const SearchSpace> space_;
  std::vector<std::vector<double>> inputs_;
  std::unique_ptr<ScenePool> workers_;
  planners::RankedStates ranked_;
  std::int64_t next_ = 0;
};

}  // namespace

std::unique_ptr<Planner> makeListPlanner(const PlanningRequest& request) {
  return std::make_unique<ListPlanner>(request);
}

}  // namespace graspkit::list
