// graspkit.plan and graspkit.PlannedGrasp: a planner from the registry, run on a step or time
// budget with the GIL released, each grasp closed and measured as `graspkit plan` does.

#include <thread>

#include <fmt/format.h>

#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/plugin/registry.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

constexpr std::int64_t kDefaultSteps = 40000;  // GraspIt!'s search length, as `graspkit plan`

struct BoundPlannedGrasp {
  std::shared_ptr<const PlanningRequest> request;
  PlannedGrasp grasp;
};

struct PlanArguments {
  std::string planner = "simann";
  std::string energy = "contact";
  std::string space = "axis-angle";
  std::string posture = "eigen";
  std::optional<std::int64_t> steps;
  std::optional<double> seconds;
  std::uint64_t seed = 1;
  int threads = 0;
  int top = 20;
  std::optional<std::string> mode;
  std::map<std::string, std::string> settings;
};

PlanningBudget budgetOf(const PlanArguments& a) {
  if (a.steps && a.seconds) throw py::value_error("give steps or seconds, not both");
  if (a.steps && *a.steps < 1) throw py::value_error("steps must be >= 1");
  if (a.seconds && !(*a.seconds > 0)) throw py::value_error("seconds must be > 0");
  PlanningBudget budget;
  if (a.seconds)
    budget.seconds = *a.seconds;
  else
    budget.steps = a.steps.value_or(kDefaultSteps);
  return budget;
}

std::shared_ptr<PlanningRequest> requestOf(const WorldHandle& world, const py::object& robot,
                                           const py::object& object, const PlanArguments& a) {
  if (a.threads < 0 || a.top < 1) throw py::value_error("threads must be >= 0 and top >= 1");
  auto request = std::make_shared<PlanningRequest>();
  request->world = std::make_shared<World>(world.world.clone());
  request->robot = toRobotIndex(world, robot);
  if (object.is_none()) {
    const auto& bodies = world.world.bodies();
    const auto found =
        std::find_if(bodies.begin(), bodies.end(), [](const Body& b) { return b.isDynamic(); });
    if (found == bodies.end()) throw py::value_error("the world has no graspable body");
    request->object = BodyRef::body(static_cast<int>(found - bodies.begin()));
  } else {
    request->object = toBodyRef(world, object, "object");
    if (request->object.kind != BodyRef::Kind::Body)
      throw py::value_error("object: a free body of the world expected, not a robot link");
  }
  request->position = parseNamed<PositionSpace>(a.space, "position space");
  request->posture = parseNamed<PostureSpace>(a.posture, "posture space");
  request->energy = a.energy;
  request->seed = a.seed;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  request->threads = a.threads > 0 ? a.threads : cores;
  request->bestListSize = a.top;
  request->options = a.settings;
  if (a.planner == "simann")
    request->options["mode"] = a.mode.value_or("restarts");
  else if (a.mode)
    throw py::value_error(
        fmt::format("mode is a simann setting; planner '{}' has none", a.planner));
  Registry::global().makeSearchEnergy(request->energy);  // an unknown name fails before planning
  return request;
}

std::vector<BoundPlannedGrasp> plan(const WorldPtr& world, const py::object& robot,
                                    const py::object& object, const PlanArguments& arguments) {
  return withWarnings([&] {
    std::shared_ptr<PlanningRequest> request = requestOf(*world, robot, object, arguments);
    auto planner = Registry::global().makePlanner(arguments.planner, *request);
    PlanningBudget budget = budgetOf(arguments);
    // Ctrl-C stops the search between reports (the planner's own thread calls this).
    bool interrupted = false;
    budget.progress = [&interrupted](const PlannerProgress&) {
      py::gil_scoped_acquire acquire;
      interrupted = interrupted || PyErr_CheckSignals() != 0;
      return !interrupted;
    };
    PlanningRun run;
    {
      py::gil_scoped_release release;
      run = runPlanner(*planner, budget);
      if (!interrupted) finishGrasps(*request, run.grasps, request->threads);
    }
    if (interrupted) throw py::error_already_set();
    std::vector<BoundPlannedGrasp> out;
    for (PlannedGrasp& g : run.grasps) out.push_back({request, std::move(g)});
    return out;
  });
}

void bindPlannedGrasp(py::module_& m) {
  py::class_<BoundPlannedGrasp>(m, "PlannedGrasp",
                                "One grasp of a plan: the pre-grasp the search found and the hand "
                                "closed on it, measured with the L1 wrench space.")
      .def_property_readonly(
          "pregrasp_pose", [](const BoundPlannedGrasp& g) { return toMatrix(g.grasp.pose); },
          "The hand's pose before closing, 4x4.")
      .def_property_readonly("pregrasp_dofs",
                             [](const BoundPlannedGrasp& g) { return toArray(g.grasp.dofs); })
      .def_property_readonly(
          "pose",
          [](const BoundPlannedGrasp& g) {
            return toMatrix(g.grasp.evaluated ? g.grasp.closed.pose : g.grasp.pose);
          },
          "The closed hand's pose (a robot type's close may move the base).")
      .def_property_readonly(
          "dofs",
          [](const BoundPlannedGrasp& g) {
            return toArray(g.grasp.evaluated ? g.grasp.closed.dofs : g.grasp.dofs);
          })
      .def_property_readonly(
          "energy", [](const BoundPlannedGrasp& g) { return g.grasp.energy; },
          "The search energy of the pre-grasp.")
      .def_property_readonly("epsilon", [](const BoundPlannedGrasp& g) { return g.grasp.epsilon; })
      .def_property_readonly("volume", [](const BoundPlannedGrasp& g) { return g.grasp.volume; })
      .def_property_readonly("contact_count",
                             [](const BoundPlannedGrasp& g) { return g.grasp.contacts; })
      .def_property_readonly("force_closure",
                             [](const BoundPlannedGrasp& g) { return g.grasp.forceClosure; })
      .def(
          "world",
          [](const BoundPlannedGrasp& g) {
            auto handle = std::make_shared<WorldHandle>();
            handle->world = graspWorld(*g.request, g.grasp);
            return handle;
          },
          "A new World with the hand as this grasp left it: saved and loaded again it gives the "
          "same contacts, epsilon and volume.")
      .def("__repr__", [](const BoundPlannedGrasp& g) {
        return fmt::format("<graspkit.PlannedGrasp epsilon {:.6g}, volume {:.6g}, {} contacts>",
                           g.grasp.epsilon, g.grasp.volume, g.grasp.contacts);
      });
}

}  // namespace

void bindPlanning(py::module_& m) {
  bindPlannedGrasp(m);
  m.def(
      "plan",
      [](const WorldPtr& world, const py::object& robot, const py::object& object,
         const std::string& planner, const std::string& energy, std::optional<std::int64_t> steps,
         std::optional<double> seconds, std::uint64_t seed, int threads, int top,
         std::optional<std::string> mode, const std::string& space, const std::string& posture,
         std::map<std::string, std::string> settings) {
        PlanArguments a{planner,
                        energy,
                        space,
                        posture,
                        steps,
                        seconds,
                        seed,
                        threads,
                        top,
                        mode,
                        std::move(settings)};
        return plan(world, robot, object, a);
      },
      py::arg("world"), py::arg("robot") = py::none(), py::arg("object") = py::none(),
      py::kw_only(), py::arg("planner") = "simann", py::arg("energy") = "contact",
      py::arg("steps") = py::none(), py::arg("seconds") = py::none(), py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("top") = 20, py::arg("mode") = py::none(),
      py::arg("space") = "axis-angle", py::arg("posture") = "eigen",
      py::arg("settings") = std::map<std::string, std::string>{},
      "Plans grasps of `object` (default: the first graspable body) with `robot` (default: the "
      "first hand) as `graspkit plan` does, best first. The world is not changed. Budget: "
      "`steps` (default 40000) or `seconds`. threads=0 uses every core. The GIL is released "
      "while it runs; Ctrl-C stops it with KeyboardInterrupt.");
}

}  // namespace graspkit::python
