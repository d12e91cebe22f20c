// graspkit.plan and graspkit.PlannedGrasp: a planner from the registry, run on a step or time
// budget with the GIL released, each grasp closed and measured as `graspkit plan` does.

#include <fmt/format.h>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

struct BoundPlannedGrasp {
  std::shared_ptr<const PlanningRequest> request;
  PlannedGrasp grasp;
};

std::vector<BoundPlannedGrasp> plan(const WorldPtr& world, const py::object& robot,
                                    const py::object& object, const host::PlanSettings& settings) {
  return withWarnings([&] {
    const int hand = toRobotIndex(*world, robot);
    BodyRef target;
    if (object.is_none()) {
      try {
        target = host::defaultObject(world->world);
      } catch (const Error& e) {
        throw py::value_error(e.what());
      }
    } else {
      target = toBodyRef(*world, object, "object");
      if (target.kind != BodyRef::Kind::Body)
        throw py::value_error("object: a free body of the world expected, not a robot link");
    }
    auto planned = std::make_shared<const World>(world->world.clone());
    // Ctrl-C stops the search between reports (the planner's own thread calls this).
    bool interrupted = false;
    auto progress = [&interrupted](const PlannerProgress&) {
      py::gil_scoped_acquire acquire;
      interrupted = interrupted || PyErr_CheckSignals() != 0;
      return !interrupted;
    };
    host::PlanResult run;
    {
      py::gil_scoped_release release;
      run = host::planGrasps(planned, hand, target, settings, progress);
    }
    if (interrupted) throw py::error_already_set();
    std::vector<BoundPlannedGrasp> out;
    for (PlannedGrasp& g : run.grasps) out.push_back({run.request, std::move(g)});
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
  const host::PlanSettings defaults;  // every default is the host layer's
  m.def(
      "plan",
      [](const WorldPtr& world, const py::object& robot, const py::object& object,
         const std::string& planner, const std::string& energy, std::optional<std::int64_t> steps,
         std::optional<double> seconds, std::uint64_t seed, int threads, int top,
         std::optional<std::string> mode, const std::string& space, const std::string& posture,
         std::map<std::string, std::string> options) {
        host::PlanSettings settings;
        settings.planner = planner;
        settings.energy = energy;
        settings.steps = steps;
        settings.seconds = seconds;
        settings.seed = seed;
        settings.threads = threads;
        settings.top = top;
        settings.mode = std::move(mode);
        settings.space = parseNamed<PositionSpace>(space, "position space");
        settings.posture = parseNamed<PostureSpace>(posture, "posture space");
        settings.options = std::move(options);
        return plan(world, robot, object, settings);
      },
      py::arg("world"), py::arg("robot") = py::none(), py::arg("object") = py::none(),
      py::kw_only(), py::arg("planner") = defaults.planner, py::arg("energy") = defaults.energy,
      py::arg("steps") = py::none(), py::arg("seconds") = py::none(),
      py::arg("seed") = defaults.seed, py::arg("threads") = defaults.threads,
      py::arg("top") = defaults.top, py::arg("mode") = py::none(),
      py::arg("space") = std::string(nameOf(defaults.space)),
      py::arg("posture") = std::string(nameOf(defaults.posture)),
      py::arg("settings") = std::map<std::string, std::string>{},
      "Plans grasps of `object` (default: the first graspable body) with `robot` (default: the "
      "first hand) as `graspkit plan` does, best first. The world is not changed. Budget: "
      "`steps` (default 40000) or `seconds`. threads=0 uses every core; mode (simann only) "
      "defaults to restarts. The GIL is released while it runs; Ctrl-C stops it with "
      "KeyboardInterrupt.");
}

}  // namespace graspkit::python
