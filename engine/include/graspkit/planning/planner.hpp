#pragma once
// The grasp-planner interface. A planner is made from a PlanningRequest (the world, the hand,
// the object, the search space, the energy, the seed and the thread count), advanced with
// step(), and asked for its ranked best list with best(). Planners come from the registry by
// name ("simann", "list", "approach", or a plugin's own); runPlanner() drives one within a step
// or time budget and reports progress, and finishGrasps() closes the hand on each result and
// measures the grasp.
//
// Determinism: for the same request (seed and thread count included) and the same step budget,
// a planner returns the same list. A time budget ends wherever the clock says, so it is not.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/collision/contact.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/hand_configuration.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/planning/search_state.hpp"

namespace graspkit {

class PlanningScene;

struct PlanningRequest {
  std::shared_ptr<const World> world;  // the planner works on clones of it
  int robot = 0;
  BodyRef object;
  PositionSpace position = PositionSpace::AxisAngle;
  PostureSpace posture = PostureSpace::Eigen;
  std::string energy = "contact";  // a registered search energy
  // An energy given in code (e.g. a Lua function); used instead of `energy` when set. A
  // planner calls it from one thread only, so it need not be thread-safe.
  SearchEnergyFactory customEnergy;
  // Where `energy` is looked up by name. Registry::makePlanner sets it to the registry (so a
  // plugin's energies are found); unset, only the built-in energies are (search_energy.hpp).
  std::function<std::unique_ptr<SearchEnergy>(const std::string& name)> energyByName;
  std::uint64_t seed = 1;
  int threads = 1;
  int bestListSize = 20;
  // Planner-specific settings, e.g. simann's "preset" and "mode"; a planner refuses keys it
  // does not know.
  std::map<std::string, std::string> options;
  // Hand poses and postures to evaluate (the list planner) or to start from.
  std::vector<SearchState> states;
};

// One planned grasp: the hand pose and DOFs the planner found (the pre-grasp) and, after
// finishGrasps(), what closing the hand there gives: the closed hand (pose, DOFs and breakaway
// state, which is what reproduces the grasp in a saved world) and its measures.
struct PlannedGrasp {
  std::vector<double> values;              // in the request's search space
  Transform pose = Transform::Identity();  // the hand's world pose before closing
  std::vector<double> dofs;                // before autograsp (the open, pre-grasp posture)
  double energy = kUnevaluatedEnergy;
  bool evaluated = false;    // set by finishGrasps()
  HandConfiguration closed;  // after autograsp (a robot type's close may move the base too)
  double epsilon = -1.0;
  double volume = 0.0;  // NaN: not measured (CloseMeasure::Ranking), until measureVolume()
  int contacts = 0;
  bool forceClosure = false;
  std::vector<Contact> contactList;  // the closed hand's contacts with the object, world frame
};

// Whether grasp a ranks before grasp b by what closing the hand gave: force closure first, then
// the larger epsilon, then the larger volume, then the lower search energy. Two grasps whose
// order would need an unknown volume must have it measured first (measureVolume()).
bool betterGrasp(const PlannedGrasp& a, const PlannedGrasp& b);

// Whether betterGrasp(a, b) or betterGrasp(b, a) would read a volume: both or neither are force
// closure, and their epsilons are equal.
bool orderNeedsVolume(const PlannedGrasp& a, const PlannedGrasp& b);

// What finishGrasp() measures of the closed hand.
enum class CloseMeasure {
  // GraspIt!'s figures: epsilon, force closure and volume from qhull with GraspIt!'s options.
  GraspIt,
  // Figures to rank many closes by. Epsilon and force closure are the exact hull's, from its
  // facet nearest the origin (HullMethod::NearestFacet: no hull is built, 30 times cheaper than
  // qhull on a force-closure grasp); the volume is NaN until measureVolume(). They equal
  // GraspIt!'s except on near-degenerate grasps, where qhull's merges move a facet;
  // measureAsGraspIt() replaces them with GraspIt!'s.
  Ranking,
};

struct PlannerProgress {
  std::int64_t steps = 0;
  double seconds = 0.0;
  double bestEnergy = kUnevaluatedEnergy;
  int states = 0;         // in the best list
  int forceClosure = -1;  // force-closure grasps found so far; -1 when the planner does not know
  double fraction = 0.0;  // of the budget spent, 0..1
};

struct PlanningBudget {
  std::optional<std::int64_t> steps;  // total steps
  std::optional<double> seconds;      // wall time
  // Called about every `reportEvery` seconds, always from the thread that runs the planner;
  // returning false stops the run.
  std::function<bool(const PlannerProgress&)> progress;
  double reportEvery = 0.25;
};

class Planner {
 public:
  virtual ~Planner() = default;
  // Advances the search by about `steps` steps in total (a concurrent planner shares them out
  // among its chains).
  virtual void step(std::int64_t steps) = 0;
  // Whether the planner has nothing more to do (a list planner that evaluated its list).
  virtual bool done() const { return false; }
  // Spends `budget` (its steps come on top of stepsDone()): steps until it is spent, the planner
  // is done, or progress returns false. The default drives step() in chunks and looks at the
  // clock between them; a planner whose work comes in larger pieces (simann's restarts)
  // watches the budget itself. Throws graspkit::Error for a budget without steps or seconds.
  virtual void run(const PlanningBudget& budget);
  // Runs once the budget is spent: a last stage, if a planner has one (none of the built-in
  // planners has: their budgets cover all their work).
  virtual void finish() {}
  virtual std::int64_t stepsDone() const = 0;
  // The best states so far, best first.
  virtual std::vector<PlannedGrasp> best() const = 0;
};

using PlannerFactory = std::function<std::unique_ptr<Planner>(const PlanningRequest&)>;

struct PlanningRun {
  std::vector<PlannedGrasp> grasps;
  std::int64_t steps = 0;
  double seconds = 0.0;
};

// Runs `planner` on the budget (Planner::run), then its last stage (Planner::finish), and
// returns its best list. Throws graspkit::Error when the budget has neither steps nor seconds.
PlanningRun runPlanner(Planner& planner, const PlanningBudget& budget);

// Closes the hand on each grasp not yet finished (autograsp from its pose and DOFs, in a fresh
// clone of the world) and measures the result with the L1 wrench space: epsilon, volume,
// contacts, force closure. Uses up to `threads` threads.
void finishGrasps(const PlanningRequest& request, std::vector<PlannedGrasp>& grasps,
                  int threads = 1);

// A clone of the request's world with the hand as `grasp` left it: closed (pose, DOFs, breakaway
// state) once finishGrasps() has run, else at the grasp's pre-grasp pose and DOFs. This is the
// world to save for a grasp: loaded again it gives the same contacts, epsilon and volume.
World graspWorld(const PlanningRequest& request, const PlannedGrasp& grasp);

// Closes the hand on one grasp in `scene` (its world is changed) and measures it (`measure`).
// `keepGoing`, when set, is asked before each step of the close; when it says stop, the close
// ends there, the grasp is left unevaluated and false is returned (a time budget running out).
//
// A planner that closes many grasps and keeps the best measures them with CloseMeasure::Ranking
// and only the grasps it returns with measureAsGraspIt(). With a gripper whose closes are mostly
// force closure (MuJoCo Menagerie's UMI gripper on the issue-40 objects), GraspIt!'s hulls of the
// closes were 29 % of the restart planner's time.
bool finishGrasp(PlanningScene& scene, PlannedGrasp& grasp,
                 const std::function<bool()>& keepGoing = {},
                 CloseMeasure measure = CloseMeasure::GraspIt);

// Measures an unknown volume (CloseMeasure::Ranking) from the grasp's contacts with `object` in
// `world` (the request's world, or any of its clones: only the object's place and mass
// properties count): the volume of GraspIt!'s hull, as CloseMeasure::GraspIt gives it. Does
// nothing to a grasp whose volume is known. A planner reads it to break ties of epsilon.
void measureVolume(const World& world, int robot, const BodyRef& object, PlannedGrasp& grasp);

// Replaces the grasp's epsilon, force closure and volume with GraspIt!'s, from its contacts with
// `object` in `world` (as measureVolume()): what CloseMeasure::GraspIt would have given.
void measureAsGraspIt(const World& world, int robot, const BodyRef& object, PlannedGrasp& grasp);

// Helpers for planner implementations.
std::shared_ptr<const SearchSpace> makeSearchSpace(const PlanningRequest& request);
// A PlanningScene on a clone of the request's world. Throws graspkit::Error for a bad request.
std::unique_ptr<PlanningScene> makePlanningScene(const PlanningRequest& request,
                                                 std::shared_ptr<const SearchSpace> space);
// The request's energy: its custom energy, else its `energy` by name through energyByName, else
// a built-in energy of that name. Throws graspkit::Error for an unknown name.
std::unique_ptr<SearchEnergy> makeSearchEnergy(const PlanningRequest& request);
// The start state: the hand where the world has it, encoded in the space (the middle of each
// range for the ellipsoid space).
SearchState startState(const PlanningScene& scene);
// A PlannedGrasp (not yet finished) for a state.
PlannedGrasp plannedGrasp(const SearchSpace& space, const SearchState& state);

}  // namespace graspkit
