#pragma once
// What every part of the Python module shares: the world handle that Body and Robot views point
// into, poses as 4x4 NumPy arrays, NumPy conversions, and the engine's warnings turned into
// Python warnings.

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "graspkit/host/world_session.hpp"
#include "graspkit/io/common/load_options.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::python {

namespace py = pybind11;

// A world as Python holds it: the host layer's world handle (world, file, model cache,
// removals). Body and Robot views hold a shared pointer to it, so a view keeps its world alive.
using WorldHandle = host::WorldSession;
using WorldPtr = std::shared_ptr<WorldHandle>;

// A free body of a world (an obstacle or a graspable object), by index. The index follows the
// world's remove_body calls made after the view was.
struct BodyView {
  BodyView(WorldPtr w, int i) : world(std::move(w)), index(i), seen(world->removedBodies.size()) {}
  WorldPtr world;
  mutable int index = 0;
  mutable std::size_t seen = 0;  // of world->removedBodies
  Body& body() const;            // throws IndexError when the body no longer exists or was removed
};

// A robot of a world, by index.
struct RobotView {
  WorldPtr world;
  int index = 0;
  const Robot& robot() const;
};

// Poses: 4x4 homogeneous matrices in mm, or a (translation, quaternion w-first) pair on input.
// A matrix must be rigid (orthonormal rotation within 1e-6, last row 0 0 0 1, finite).
Transform toTransform(const py::handle& pose);
py::array_t<double> toMatrix(const Transform& pose);

py::array_t<double> toArray(const Vector3& v);
py::array_t<double> toArray(std::span<const double> values);
py::array_t<double> toArray(const Eigen::VectorXd& values);
// A 1-D sequence of `expected` finite numbers (any length when expected < 0); `what` names the
// argument in the error.
std::vector<double> toVector(const py::handle& values, long expected, const char* what);
Vector3 toVector3(const py::handle& values, const char* what);
// An (N, 3) array of doubles, C-contiguous (copied only when it is not already).
py::array_t<double, py::array::c_style | py::array::forcecast> toPoints(const py::handle& values,
                                                                        const char* what);

// The engine's warnings queue up wherever they are raised (any thread); flushWarnings() turns
// them into Python warnings (graspkit.GraspkitWarning and its per-kind subclasses). Calls that
// can warn run through withWarnings.
void installWarningHandler(py::module_& m);
void flushWarnings();
template <class Function>
auto withWarnings(Function&& function) {
  if constexpr (std::is_void_v<decltype(function())>) {
    function();
    flushWarnings();
  } else {
    auto result = function();
    flushWarnings();
    return result;
  }
}

// The body reference named by a Python value: a Body view of `world`, or a name.
BodyRef toBodyRef(const WorldHandle& world, const py::handle& body, const char* what);
// A robot by Robot view of `world`, 0-based index or name; none gives the world's first hand.
int toRobotIndex(const WorldHandle& world, const py::handle& robot);

// The load options load_world, add_robot and plan_dataset take, as `graspkit`'s load flags:
// model roots, generic robots, and for URDF hands the package path, palm, materials, closing
// directions ({dof: "+" or "-"}) and SRDF.
struct LoadArguments {
  std::vector<std::filesystem::path> roots;
  bool genericRobots = false;
  std::vector<std::filesystem::path> packagePath;
  std::string palm;
  std::string urdfMaterial;
  std::map<std::string, std::string> linkMaterials;
  std::map<int, std::string> close;
  std::filesystem::path srdf;
  LoadOptions options() const;
};

void bindErrors(py::module_& m);
void bindPoses(py::module_& m);
void bindWorld(py::module_& m);
void bindRobot(py::module_& m);
void bindGrasp(py::module_& m);
void bindRays(py::module_& m);
void bindPlanning(py::module_& m);
void bindPlugins(py::module_& m);
void bindDynamics(py::module_& m);
void bindDatasets(py::module_& m);

}  // namespace graspkit::python
