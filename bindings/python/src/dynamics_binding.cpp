// World.step, World.simulate and graspkit.validate: the engine's dynamics and grasp validation
// with the host layer's settings and defaults, as `graspkit simulate` and `graspkit validate`
// run them. The GIL is released while they run.

#include <cmath>

#include <fmt/format.h>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/host/simulation_task.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

py::dict stepReport(const StepReport& report) {
  py::dict d;
  d["time"] = report.time;
  d["contacts"] = report.contacts;
  d["active_contacts"] = report.activeContacts;
  d["joint_limits"] = report.jointLimits;
  return d;
}

py::dict simulateWorld(WorldHandle& w, double seconds, double dt, const py::object& gravity,
                       bool autograsp, int every, bool trajectory) {
  host::SimulationSettings settings;
  settings.seconds = seconds;
  settings.dt = dt;
  settings.autograsp = autograsp;
  settings.every = every;
  if (!gravity.is_none()) settings.gravity = toVector3(gravity, "gravity");
  std::vector<std::string> frames;
  host::SimulationOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = host::simulateWorld(w.world, settings, [&](const World& world) {
      if (trajectory) frames.push_back(dynamicStateJson(world));
    });
  }
  py::dict d = stepReport(outcome.result.last);
  d["completed"] = outcome.completed;
  d["stop_reason"] = outcome.stopReason;
  d["steps"] = outcome.result.steps;
  d["time"] = w.world.time();
  if (!outcome.completed)
    d["failure_state"] = py::module_::import("json").attr("loads")(outcome.failureState);
  if (trajectory) {
    py::list states;
    auto loads = py::module_::import("json").attr("loads");
    for (const std::string& frame : frames) states.append(loads(frame));
    d["trajectory"] = states;
  }
  return d;
}

py::dict validationDict(const ValidationResult& result) {
  py::list directions;
  for (int k = 0; k < 6; ++k) {
    const DirectionResult& r = result.directions[static_cast<std::size_t>(k)];
    py::dict d;
    d["direction"] = std::string(host::kValidationDirections[static_cast<std::size_t>(k)]);
    d["held"] = r.held;
    d["slip_mm"] = r.slip;
    d["turn_deg"] = r.turn * 180.0 / M_PI;
    d["seconds"] = r.seconds;
    if (!r.failure.empty()) d["failure"] = r.failure;
    directions.append(d);
  }
  py::dict d;
  d["held"] = result.held;
  d["directions_held"] = result.directionsHeld;
  d["settle_seconds"] = result.settleSeconds;
  d["directions"] = directions;
  return d;
}

}  // namespace

void bindDynamics(py::module_& m) {
  const host::SimulationSettings defaults;
  py::class_<WorldHandle, WorldPtr> world =
      py::reinterpret_borrow<py::class_<WorldHandle, WorldPtr>>(m.attr("World"));
  world.def(
      "step",
      [](WorldHandle& w, double dt) {
        StepReport report;
        {
          py::gil_scoped_release release;
          report = step(w.world, dt);
        }
        return stepReport(report);
      },
      py::arg("dt") = defaults.dt,
      "Advances the world's dynamics by dt seconds -> {time, contacts, active_contacts, "
      "joint_limits}. A state the step cannot continue from raises graspkit.Error.");
  world.def("simulate", &simulateWorld, py::kw_only(), py::arg("seconds") = defaults.seconds,
            py::arg("dt") = defaults.dt, py::arg("gravity") = py::none(),
            py::arg("autograsp") = defaults.autograsp, py::arg("every") = defaults.every,
            py::arg("trajectory") = false,
            "Steps the world as `graspkit simulate` does -> {completed, stop_reason, steps, time, "
            "contacts, active_contacts, ...}. gravity: (x, y, z) mm/s^2 (default: the world's); "
            "autograsp drives the first hand's DOFs towards their closing limits; trajectory "
            "adds the state every `every` steps (and before the first), as --trajectory writes "
            "it. A simulation that blows up ends with completed False, its reason and "
            "failure_state.");
  m.def(
      "validate",
      [](const WorldPtr& w, double seconds) {
        ValidationRequest request;
        request.seconds = seconds;
        const World world = w->world.clone();
        ValidationResult result;
        {
          py::gil_scoped_release release;
          result = host::validateWorld(world, request);
        }
        return validationDict(result);
      },
      py::arg("world"), py::kw_only(), py::arg("seconds") = ValidationRequest{}.seconds,
      "Labels the grasp a world holds (its first hand closed on its first graspable body) as "
      "`graspkit validate` does: the object's weight turned along +x, -x, +y, -y, +z, -z -> "
      "{held, directions_held, settle_seconds, directions: [{direction, held, slip_mm, turn_deg, "
      "seconds}]}. "
      "The world is not changed.");
}

}  // namespace graspkit::python
