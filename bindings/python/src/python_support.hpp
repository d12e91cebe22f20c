#pragma once
// What every part of the Python module shares: the world handle that Body and Robot views point
// into, poses as 4x4 NumPy arrays, NumPy conversions, and the engine's warnings turned into
// Python warnings.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::python {

namespace py = pybind11;

// A world as Python holds it. Body and Robot views hold a shared pointer to it, so a view keeps
// its world alive. Meshes loaded through one world are cached for the next file it loads.
struct WorldHandle {
  World world;
  std::filesystem::path file;  // where it was loaded from or last saved; empty for a new world
  ModelCache cache;
};
using WorldPtr = std::shared_ptr<WorldHandle>;

// A free body of a world (an obstacle or a graspable object), by index.
struct BodyView {
  WorldPtr world;
  int index = 0;
  Body& body() const;  // throws IndexError when the body no longer exists
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

void bindErrors(py::module_& m);
void bindPoses(py::module_& m);
void bindWorld(py::module_& m);
void bindRobot(py::module_& m);
void bindGrasp(py::module_& m);
void bindRays(py::module_& m);
void bindPlanning(py::module_& m);
void bindPlugins(py::module_& m);

}  // namespace graspkit::python
