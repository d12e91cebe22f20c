// graspkit.Robot: DOFs and their limits, poses of the base and links, eigengrasps, inverse
// kinematics, and the hand's motions (autograsp, open, approach).

#include <fmt/format.h>

#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/planning/eigengrasp_map.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

// What a motion of the hand did (autograsp, approach_to_contact).
struct Motion {
  py::array_t<double> dofs;
  int steps = 0;
  std::string ended;
  int contactCount = 0;
};

Motion toMotion(const AutoGraspResult& result) {
  return {toArray(result.dofValues), result.iterations, std::string(nameOf(result.end)),
          static_cast<int>(result.contacts.size())};
}

LimitPolicy toLimitPolicy(const std::string& limits) {
  if (limits == "clamp") return LimitPolicy::Clamp;
  if (limits == "ignore") return LimitPolicy::Ignore;
  throw py::value_error(
      fmt::format("limits '{}': \"clamp\", \"ignore\" or \"error\" expected", limits));
}

void setDofs(const RobotView& view, const py::object& values, const std::string& limits) {
  const Robot& robot = view.robot();
  const std::vector<double> v = toVector(values, robot.dofCount(), "dofs");
  if (limits == "error") {
    for (int d = 0; d < robot.dofCount(); ++d) {
      const Dof& dof = robot.model().dofs[static_cast<std::size_t>(d)];
      if (v[d] < dof.min || v[d] > dof.max)
        throw py::value_error(fmt::format("dof {}: {} is outside its range [{}, {}]", d,
                                          v[static_cast<std::size_t>(d)], dof.min, dof.max));
    }
  }
  view.world->world.setDofValues(view.index, v,
                                 limits == "error" ? LimitPolicy::Clamp : toLimitPolicy(limits));
}

py::dict eigengrasps(const RobotView& view) {
  const EigengraspMap map(view.robot().model());
  py::array_t<double> directions({map.size(), map.dofCount()});
  auto d = directions.mutable_unchecked<2>();
  std::vector<double> min, max;
  for (int i = 0; i < map.size(); ++i) {
    const Eigen::VectorXd direction = map.direction(i);
    for (int k = 0; k < map.dofCount(); ++k) d(i, k) = direction[k];
    min.push_back(map.minAmplitude(i));
    max.push_back(map.maxAmplitude(i));
  }
  py::dict out;
  out["directions"] = directions;
  out["min"] = toArray(min);
  out["max"] = toArray(max);
  out["origin"] = toArray(map.origin());
  out["norm"] = toArray(map.norm());
  out["identity"] = view.robot().model().eigengrasps.identity;
  return out;
}

py::list linkPoses(const Robot& robot) {
  py::list chains;
  for (const auto& chain : robot.linkPoses()) {
    py::array_t<double> poses(
        {static_cast<py::ssize_t>(chain.size()), py::ssize_t{4}, py::ssize_t{4}});
    auto a = poses.mutable_unchecked<3>();
    for (std::size_t l = 0; l < chain.size(); ++l)
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) a(static_cast<py::ssize_t>(l), r, c) = chain[l].matrix()(r, c);
    chains.append(poses);
  }
  return chains;
}

void bindResults(py::module_& m) {
  py::class_<Motion>(m, "Motion", "What a motion of the hand did.")
      .def_readonly("dofs", &Motion::dofs, "The DOF values it ended at.")
      .def_readonly("steps", &Motion::steps)
      .def_readonly("ended", &Motion::ended,
                    "\"settled\", \"contact\", \"iteration_limit\", ... (GraspIt!'s reasons)")
      .def_readonly("contact_count", &Motion::contactCount,
                    "Contacts of the hand's links after the motion.")
      .def("__repr__", [](const Motion& motion) {
        return fmt::format("<graspkit.Motion ended {} after {} steps, {} contacts>", motion.ended,
                           motion.steps, motion.contactCount);
      });
  py::class_<IkResult>(m, "IkResult", "An inverse-kinematics answer.")
      .def_readonly("success", &IkResult::success)
      .def_property_readonly("dofs",
                             [](const IkResult& r) -> py::object {
                               if (!r.success) return py::none();
                               return toArray(r.dofValues);
                             })
      .def_readonly("failure", &IkResult::failure, "Why not, when not a success.")
      .def_readonly("iterations", &IkResult::iterations, "0 for a closed form.")
      .def("__bool__", [](const IkResult& r) { return r.success; });
}

void bindRobotClass(py::module_& m) {
  py::class_<RobotView>(m, "Robot", "A robot of a world (a hand, an arm). A view of its world.")
      .def_property_readonly("name", [](const RobotView& r) { return r.robot().name(); })
      .def_property_readonly("index", [](const RobotView& r) { return r.index; })
      .def_property_readonly(
          "type", [](const RobotView& r) { return r.robot().model().type; },
          "The <robot type> attribute (Hand, Barrett, Puma560, ...).")
      .def_property_readonly("is_hand", [](const RobotView& r) { return r.robot().model().isHand; })
      .def_property_readonly("dof_count", [](const RobotView& r) { return r.robot().dofCount(); })
      .def_property_readonly(
          "dofs", [](const RobotView& r) { return toArray(r.robot().dofValues()); },
          "DOF values: radians, or mm for prismatic DOFs.")
      .def("set_dofs", &setDofs, py::arg("values"), py::kw_only(), py::arg("limits") = "clamp",
           "Sets every DOF. limits: \"clamp\" into each range, \"ignore\" them (as GraspIt! "
           "loads worlds) or \"error\" (ValueError when one is outside).")
      .def_property_readonly(
          "dof_limits",
          [](const RobotView& r) {
            std::vector<double> min, max;
            for (const Dof& dof : r.robot().model().dofs) {
              min.push_back(dof.min);
              max.push_back(dof.max);
            }
            return py::make_tuple(toArray(min), toArray(max));
          },
          "(min, max) arrays.")
      .def_property(
          "pose", [](const RobotView& r) { return toMatrix(r.robot().pose()); },
          [](const RobotView& r, const py::object& pose) {
            r.world->world.setRobotPose(r.index, toTransform(pose));
          },
          "The base (palm) frame in the world, 4x4, mm.")
      .def_property_readonly("chain_count",
                             [](const RobotView& r) { return r.robot().model().chains.size(); })
      .def(
          "link_poses", [](const RobotView& r) { return linkPoses(r.robot()); },
          "One (links, 4, 4) array per chain: each link's frame in the world.")
      .def(
          "link_names",
          [](const RobotView& r) {
            std::vector<std::vector<std::string>> names;
            for (const auto& chain : r.robot().model().chains) {
              names.emplace_back();
              for (const Link& link : chain.links) names.back().push_back(link.name);
            }
            return names;
          },
          "The link names chain by chain (<robot>_chain<c>_link<l>).")
      .def("eigengrasps", &eigengrasps,
           "{'directions': (E, D), 'min', 'max', 'origin', 'norm', 'identity'}: dofs = origin + "
           "norm * (a @ directions).")
      .def(
          "eigengrasp_amplitudes",
          [](const RobotView& r) {
            const auto values = r.robot().dofValues();
            const Eigen::VectorXd a =
                EigengraspMap(r.robot().model())
                    .amplitudes(Eigen::Map<const Eigen::VectorXd>(
                        values.data(), static_cast<Eigen::Index>(values.size())));
            return toArray(a);
          },
          "The amplitudes nearest (least squares) to the current DOFs.")
      .def(
          "set_eigengrasp_amplitudes",
          [](const RobotView& r, const py::object& amplitudes) {
            const EigengraspMap map(r.robot().model());
            const std::vector<double> a = toVector(amplitudes, map.size(), "amplitudes");
            const Eigen::VectorXd dofs =
                map.dofs(Eigen::Map<const Eigen::VectorXd>(a.data(), map.size()));
            r.world->world.setDofValues(r.index, std::span<const double>(dofs.data(), dofs.size()));
          },
          py::arg("amplitudes"), "Sets the DOFs from amplitudes, each clamped into its range.")
      .def(
          "inverse_kinematics",
          [](const RobotView& r, const py::object& pose, int chain, int max_iterations) {
            const int chains = static_cast<int>(r.robot().model().chains.size());
            if (chain < 0 || chain >= chains)
              throw py::index_error(
                  fmt::format("chain {} out of range (the robot has {})", chain, chains));
            if (max_iterations < 1) throw py::value_error("max_iterations must be >= 1");
            IkRequest request;
            request.chain = chain;
            request.maxIterations = max_iterations;
            return inverseKinematics(r.robot(), toTransform(pose), request);
          },
          py::arg("pose"), py::kw_only(), py::arg("chain") = 0, py::arg("max_iterations") = 200,
          "DOF values that put the end of `chain` (its last link's frame) at `pose`; the robot "
          "type's closed form where it has one (Puma560), else GraspIt!'s iterative solver. "
          "The robot does not move.")
      .def(
          "autograsp",
          [](const RobotView& r, double speed, bool stop_at_contact, int max_steps) {
            return withWarnings([&] {
              AutoGraspOptions options;
              options.speedFactor = speed;
              options.stopAtContact = stop_at_contact;
              options.maxIterations = max_steps;
              if (!std::isfinite(speed) || max_steps < 1)
                throw py::value_error("speed must be finite and max_steps >= 1");
              return toMotion(autoGrasp(r.world->world, r.index, options));
            });
          },
          py::kw_only(), py::arg("speed") = 1.0, py::arg("stop_at_contact") = false,
          py::arg("max_steps") = 500,
          "Closes the hand as its type closes (GraspIt!'s autoGrasp); a negative speed opens.")
      .def(
          "open", [](const RobotView& r) { return openUntilFree(r.world->world, r.index); },
          "Opens the hand until it is free of collisions; whether it ended free.")
      .def(
          "approach_to_contact",
          [](const RobotView& r, double max_distance, double step, const py::object& direction) {
            ApproachOptions options;
            options.maxDistance = max_distance;
            options.step = step;
            if (!direction.is_none()) options.direction = toVector3(direction, "direction");
            if (!(max_distance >= 0) || !(step > 0))
              throw py::value_error("max_distance must be >= 0 and step > 0");
            return toMotion(approachToContact(r.world->world, r.index, options));
          },
          py::kw_only(), py::arg("max_distance") = 500.0, py::arg("step") = 10.0,
          py::arg("direction") = py::none(),
          "Moves the hand in a straight line (its approach direction, or `direction` in the "
          "world) until it touches something; motion.ended == 'contact' when it did.")
      .def("__repr__", [](const RobotView& r) {
        return fmt::format("<graspkit.Robot '{}' ({}, {} DOFs)>", r.robot().name(),
                           r.robot().model().type, r.robot().dofCount());
      });
}

}  // namespace

void bindRobot(py::module_& m) {
  bindResults(m);
  bindRobotClass(m);
}

}  // namespace graspkit::python
