// Poses and vectors between NumPy and Eigen. A pose is a 4x4 homogeneous matrix (mm) on the way
// out; on the way in, a 4x4 matrix or a (translation, quaternion w-first) pair.

#include <cmath>

#include <fmt/format.h>

#include "python_support.hpp"

namespace graspkit::python {
namespace {

constexpr double kRigidTolerance = 1e-6;

Transform fromMatrix(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw py::value_error("a pose is a 4x4 matrix or a (translation, quaternion) pair");
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = a.at(r, c);
  if (!m.allFinite()) throw py::value_error("pose: a value is not a finite number");
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > kRigidTolerance)
    throw py::value_error("pose: the last row must be 0 0 0 1");
  const Eigen::Matrix3d rotation = m.topLeftCorner<3, 3>();
  const double off = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  if (off > kRigidTolerance || rotation.determinant() < 0)
    throw py::value_error(
        fmt::format("pose: the upper-left 3x3 is not a rotation (|R^T R - I| = {:.3g})", off));
  // Through a unit quaternion, so that the rotation is orthonormal to the last bit.
  if (const char* why = translationProblem(m.topRightCorner<3, 1>()))
    throw py::value_error(std::string("pose: the translation ") + why);
  return makeTransform(m.topRightCorner<3, 1>(), Quaternion(rotation).normalized());
}

}  // namespace

Transform toTransform(const py::handle& pose) {
  if (py::isinstance<py::tuple>(pose) && py::len(pose) == 2) {
    const auto parts = pose.cast<py::tuple>();
    const Vector3 t = toVector3(parts[0], "pose translation");
    if (const char* why = translationProblem(t))
      throw py::value_error(std::string("pose translation ") + why);
    const std::vector<double> q = toVector(parts[1], 4, "pose quaternion (w, x, y, z)");
    const std::optional<Quaternion> rotation = unitQuaternion(q[0], q[1], q[2], q[3]);
    if (!rotation)
      throw py::value_error("pose quaternion is zero or not finite: it names no rotation");
    return makeTransform(t, *rotation);
  }
  return fromMatrix(py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(pose));
}

py::array_t<double> toMatrix(const Transform& pose) {
  py::array_t<double> out({4, 4});
  auto m = out.mutable_unchecked<2>();
  const Eigen::Matrix4d& h = pose.matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = h(r, c);
  return out;
}

py::array_t<double> toArray(const Vector3& v) {
  py::array_t<double> out(3);
  for (int i = 0; i < 3; ++i) out.mutable_at(i) = v[i];
  return out;
}

py::array_t<double> toArray(std::span<const double> values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::array_t<double> toArray(const Eigen::VectorXd& values) {
  return toArray(std::span<const double>(values.data(), static_cast<std::size_t>(values.size())));
}

std::vector<double> toVector(const py::handle& values, long expected, const char* what) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!a || a.ndim() != 1)
    throw py::value_error(fmt::format("{}: a 1-D sequence of numbers expected", what));
  if (expected >= 0 && a.shape(0) != expected)
    throw py::value_error(
        fmt::format("{}: {} values expected, got {}", what, expected, a.shape(0)));
  std::vector<double> out(a.data(), a.data() + a.shape(0));
  for (double v : out)
    if (!std::isfinite(v)) throw py::value_error(fmt::format("{}: {} is not finite", what, v));
  return out;
}

Vector3 toVector3(const py::handle& values, const char* what) {
  const std::vector<double> v = toVector(values, 3, what);
  return {v[0], v[1], v[2]};
}

py::array_t<double, py::array::c_style | py::array::forcecast> toPoints(const py::handle& values,
                                                                        const char* what) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!a || a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{}: an (N, 3) array expected", what));
  return a;
}

void bindPoses(py::module_& m) {
  m.def(
      "pose",
      [](const py::object& translation, const py::object& quaternion) {
        return toMatrix(toTransform(py::make_tuple(translation, quaternion)));
      },
      py::arg("translation") = py::make_tuple(0.0, 0.0, 0.0),
      py::arg("quaternion") = py::make_tuple(1.0, 0.0, 0.0, 0.0),
      "The 4x4 pose of a translation (mm) and a unit quaternion (w, x, y, z; normalised here).");
  m.def(
      "translation_quaternion",
      [](const py::object& pose) {
        const Transform t = toTransform(pose);
        Quaternion q(t.rotation());
        if (q.w() < 0) q.coeffs() = -q.coeffs();
        return py::make_tuple(toArray(Vector3(t.translation())),
                              toArray(std::vector<double>{q.w(), q.x(), q.y(), q.z()}));
      },
      py::arg("pose"),
      "The (translation, quaternion w-first) of a pose; the quaternion has w >= 0.");
  m.def(
      "axis_angle",
      [](const py::object& axis, double angle, const py::object& translation) {
        const Vector3 a = toVector3(axis, "axis");
        if (a.norm() < 1e-12) throw py::value_error("axis is zero");
        if (!std::isfinite(angle)) throw py::value_error("angle is not finite");
        return toMatrix(makeTransform(toVector3(translation, "translation"),
                                      Quaternion(Eigen::AngleAxisd(angle, a.normalized()))));
      },
      py::arg("axis"), py::arg("angle"), py::arg("translation") = py::make_tuple(0.0, 0.0, 0.0),
      "The pose that rotates by `angle` radians about `axis`, then translates (mm).");
}

}  // namespace graspkit::python
