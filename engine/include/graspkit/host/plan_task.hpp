#pragma once
// Planning as every front end offers it: the settings with their one set of defaults (what
// `graspkit plan`, Lua's graspkit.planner, Python's graspkit.plan and graspkit_plan_grasps all
// start from), and the whole task: plan, then close the hand on each grasp and measure it.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/model/body_ref.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"

namespace graspkit::host {

// GraspIt!'s search length (its planner's 40000 annealing steps): the budget when none is given.
inline constexpr std::int64_t kDefaultPlanSteps = 40000;
// simann's mode when none is given: any-time, and the best grasps per step (docs/plugins.md).
inline constexpr const char* kDefaultMode = "restarts";

struct PlanSettings {
  std::string planner = "simann";  // a registered planner
  std::string energy = "contact";  // a registered search energy (GraspIt!'s names too)
  PositionSpace space = PositionSpace::AxisAngle;
  PostureSpace posture = PostureSpace::Eigen;
  // simann's mode: "restarts" (many short searches, each closing its best states; any-time) or
  // "anneal" (GraspIt!'s single search); kDefaultMode when unset. Other planners have none.
  std::optional<std::string> mode;
  std::string preset;                          // simann's schedule; the planner's when empty
  std::map<std::string, std::string> options;  // other planner-specific settings
  // The budget: steps or seconds, not both; neither means kDefaultPlanSteps.
  std::optional<std::int64_t> steps;
  std::optional<double> seconds;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: one per core (resolveThreads)
  int top = 20;     // the best list's size
};

// The thread count `threads` stands for: itself when positive, the machine's cores when 0.
// Throws graspkit::Error for a negative count.
int resolveThreads(int threads);

// The planning request the settings describe, on `world` (not changed: planners work on clones).
// Checks everything that can be checked before planning: the robot and object, the energy's
// name, the mode (only simann has one), the thread count and the best list's size. Throws
// InvalidSetting (host/invalid_setting.hpp) naming a bad setting, graspkit::Error for an unknown
// energy or a robot or object the world does not have.
PlanningRequest planningRequest(std::shared_ptr<const World> world, int robot, BodyRef object,
                                const PlanSettings& settings);
// The budget the settings describe. Throws InvalidSetting for steps and seconds both given, or
// either not positive.
PlanningBudget planningBudget(const PlanSettings& settings);

// The virtual contacts the planner's energies use: the hand's own, or (for a hand that has none)
// those derived from its geometry and closing motion.
struct PlanningContacts {
  std::size_t count = 0;
  bool derived = false;
};
// Throws graspkit::Error when the hand has none and none can be derived.
PlanningContacts planningContacts(const World& world, int robot);

struct PlanResult {
  std::shared_ptr<const PlanningRequest> request;
  std::vector<PlannedGrasp> grasps;  // best first, each closed and measured (finishGrasps)
  std::int64_t steps = 0;
  double seconds = 0.0;
  PlanningContacts contacts;
  bool stopped = false;  // progress returned false: the grasps found until then, closed
};

// Plans with the settings' planner and budget, then closes the hand on each grasp and measures
// it. `progress` is called from the calling thread about four times a second; returning false
// stops the search. Throws graspkit::Error as planningRequest, planningBudget and the planner do.
PlanResult planGrasps(std::shared_ptr<const World> world, int robot, BodyRef object,
                      const PlanSettings& settings,
                      std::function<bool(const PlannerProgress&)> progress = {});

}  // namespace graspkit::host
