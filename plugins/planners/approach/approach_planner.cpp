#include "approach_planner.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "approach_samples.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/scene_pool.hpp"
#include "graspkit/raycast/ray_scene.hpp"
#include "sampling.hpp"

namespace graspkit::approach {

namespace {

// Clearance between the hand's bounding sphere and the object's at the start, mm.
constexpr double kStartClearance = 10.0;

struct Settings {
  int directions = 64;
  int rolls = 4;
};

int count(const std::string& key, const std::string& text) {
  try {
    std::size_t used = 0;
    const long value = std::stol(text, &used);
    if (used == text.size() && value >= 1 && value <= 1000000) return static_cast<int>(value);
  } catch (const std::exception&) {
  }
  throw Error(
      fmt::format("approach: option {} = '{}' is not a whole number in [1, 1000000]", key, text));
}

Settings settingsFrom(const PlanningRequest& request) {
  Settings s;
  for (const auto& [key, value] : request.options) {
    if (key == "directions")
      s.directions = count(key, value);
    else if (key == "rolls")
      s.rolls = count(key, value);
    else
      throw Error(fmt::format("approach: unknown option '{}'; known: directions, rolls", key));
  }
  return s;
}

// One approach: where the hand starts, how far its approach frame may travel.
struct Sample {
  Transform start = Transform::Identity();
  double travel = 0.0;
  bool valid = false;  // the line through the centre meets the object
};

// The open posture: each closing DOF at the limit it opens toward, the rest as the world has
// them; then the nearest posture the search space can hold.
std::vector<double> openDofs(const Robot& hand, const SearchSpace& space) {
  const auto& dofs = hand.model().dofs;
  std::vector<double> open(hand.dofValues().begin(), hand.dofValues().end());
  for (std::size_t d = 0; d < dofs.size(); ++d) {
    if (dofs[d].defaultVelocity > 0) open[d] = dofs[d].min;
    if (dofs[d].defaultVelocity < 0) open[d] = dofs[d].max;
  }
  return space.dofs(space.encode(hand.pose(), open));
}

// An upper bound on how far any point of the hand is from its approach frame's origin, with
// the DOFs at `dofs`: per link, the CoG's distance plus the link's own radius.
double handReach(PlanningScene& scene, const std::vector<double>& dofs) {
  World& world = scene.world();
  world.setDofValues(scene.robot(), dofs, LimitPolicy::Clamp);
  const Vector3 origin = (scene.hand().pose() * scene.space().approachFrame()).translation();
  double reach = 0.0;
  for (const BodyRef& link : scene.handLinks()) {
    const BodyModel& model = bodyModel(world, link);
    const Vector3 cog = bodyPose(world, link) * model.cog;
    reach = std::max(reach, (cog - origin).norm() + model.maxRadius);
  }
  return reach;
}

class ApproachPlanner final : public Planner {
 public:
  explicit ApproachPlanner(const PlanningRequest& request)
      : space_(makeSearchSpace(request)), ranked_(request.bestListSize) {
    if (request.position != PositionSpace::Complete && request.position != PositionSpace::AxisAngle)
      throw Error(fmt::format(
          "approach: the {} position space cannot hold the poses this planner finds; use "
          "complete or axis-angle",
          nameOf(request.position)));
    if (request.threads < 1)
      throw Error(fmt::format("approach: {} threads is not valid", request.threads));
    if (request.bestListSize < 1)
      throw Error(fmt::format("approach: a best list of {} is not valid", request.bestListSize));
    settings_ = settingsFrom(request);
    workers_ = std::make_unique<ScenePool>(request, space_);
    PlanningScene& scene = workers_->scene(0);
    open_ = openDofs(scene.hand(), *space_);
    samples_ = makeSamples(scene, handReach(scene, open_));
  }

  void step(std::int64_t steps) override {
    const auto total = static_cast<std::int64_t>(samples_.size());
    // A step of fewer samples than workers would leave workers idle: take at least one each.
    const std::int64_t end =
        std::min(total, next_ + std::max<std::int64_t>(steps, workers_->capacity()));
    std::vector<std::optional<SearchState>> results(static_cast<std::size_t>(end - next_));
    workers_->run(next_, end, [&](int w, std::int64_t i) {
      results[static_cast<std::size_t>(i - next_)] =
          approach(workers_->scene(w), workers_->energy(w), samples_[static_cast<std::size_t>(i)]);
    });
    for (auto& r : results)
      if (r) ranked_.offer(std::move(*r));
    next_ = end;
  }

  bool done() const override { return next_ >= static_cast<std::int64_t>(samples_.size()); }
  std::int64_t stepsDone() const override { return next_; }

  std::vector<PlannedGrasp> best() const override {
    std::vector<PlannedGrasp> grasps;
    for (const SearchState& s : ranked_.states()) grasps.push_back(plannedGrasp(*space_, s));
    return grasps;
  }

 private:
  // Every sample's start pose and travel, from rays cast at the object alone.
  std::vector<Sample> makeSamples(const PlanningScene& scene, double reach) const {
    const World& world = scene.world();
    const BodyRef object = scene.object();
    RaySceneOptions only;
    only.include = [object](const BodyRef& body) { return body == object; };
    const RayScene rays(world, only);
    const Transform objectPose = bodyPose(world, object);
    const Vector3 centre = objectPose * bodyModel(world, object).cog;
    const double radius = scene.objectRadius();
    const Matrix3 axes = objectPose.linear();
    const Transform approachInverse = space_->approachFrame().inverse();

    std::vector<Sample> samples;
    for (const Vector3& unit : fibonacciSphere(settings_.directions)) {
      const Vector3 outward = axes * unit;
      const Vector3 approach = -outward;
      // The first point of the object on the line from outside its bounding sphere inward.
      Ray ray;
      ray.origin = centre + (radius + kStartClearance) * outward;
      ray.direction = approach;
      ray.tmax = 2.0 * (radius + kStartClearance);
      const std::optional<RayHit> hit = rays.intersect(ray);
      const Vector3 startOrigin = centre + (radius + reach + kStartClearance) * outward;
      for (int k = 0; k < settings_.rolls; ++k) {
        const double roll = 2.0 * std::numbers::pi * k / settings_.rolls;
        Transform frame = Transform::Identity();
        frame.linear() = approachRotation(approach, axes.col(0), axes.col(1), roll);
        frame.translation() = startOrigin;
        Sample s;
        s.start = frame * approachInverse;
        s.valid = hit.has_value();
        if (hit) s.travel = (hit->point - startOrigin).norm();
        samples.push_back(s);
      }
    }
    return samples;
  }

  std::optional<SearchState> approach(PlanningScene& scene, SearchEnergy& energy,
                                      const Sample& sample) const {
    if (!sample.valid) return std::nullopt;
    World& world = scene.world();
    for (int j = 0; j < static_cast<int>(scene.hand().breakaway().size()); ++j)
      world.setBreakaway(scene.robot(), j, BreakawayState{});
    world.setRobotPose(scene.robot(), sample.start);
    world.setDofValues(scene.robot(), open_, LimitPolicy::Clamp);
    if (scene.handCollides()) return std::nullopt;
    ApproachOptions options;
    options.maxDistance = sample.travel;
    approachToContact(world, scene.robot(), options);
    const std::optional<std::vector<double>> values =
        planners::encodeExactly(*space_, scene.hand().pose(), open_);
    if (!values) return std::nullopt;
    const std::optional<double> e = evaluateState(scene, energy, *values);
    if (!e) return std::nullopt;
    return SearchState{*values, *e};
  }

  std::shared_ptr<const SearchSpace> space_;
  Settings settings_;
  std::unique_ptr<ScenePool> workers_;
  std::vector<double> open_;
  std::vector<Sample> samples_;
  planners::RankedStates ranked_;
  std::int64_t next_ = 0;
};

}  // namespace

std::unique_ptr<Planner> makeApproachPlanner(const PlanningRequest& request) {
  return std::make_unique<ApproachPlanner>(request);
}

}  // namespace graspkit::approach
