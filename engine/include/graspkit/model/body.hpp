#pragma once
// A body as described by a Body file: geometry, material and mass properties. BodyModel is
// immutable and shared by every world and every link that uses the same file; where a body is
// and how it moves is per-world state (Body).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include "graspkit/base/enum_names.hpp"

#include "graspkit/geometry/mesh.hpp"
#include "graspkit/model/material.hpp"

namespace graspkit {

inline constexpr double kDefaultMass = 300.0;  // g, GraspIt!'s default when <mass> is missing

struct BodyModel {
  std::string name;                    // the file stem
  std::filesystem::path file;          // the Body XML (or a bare geometry file)
  std::filesystem::path geometryFile;  // absolute path of the geometry
  std::string geometryType = "Inventor";
  std::shared_ptr<const TriangleMesh> mesh;  // scaled and offset as the file says, mm

  Material material = Material::Wood;
  std::optional<double> youngs;  // Pa; presence makes the body elastic (soft contacts)
  std::optional<double> normalCompliance;
  std::optional<double> shearCompliance;
  bool useFlockOfBirds = false;
  int flockOfBirdsNumber = -1;

  Vector3 geometryScaling = Vector3::Ones();
  Transform geometryOffset = Transform::Identity();

  // Mass properties. The inertia is per unit mass, about the CoG, in body axes (mm^2).
  double mass = kDefaultMass;
  Vector3 cog = Vector3::Zero();
  Matrix3 inertia = Matrix3::Identity();
  double maxRadius = 0.0;  // largest CoG-to-vertex distance, mm
  bool massFromFile = false;
  bool cogFromFile = false;
  bool inertiaFromFile = false;
  // The mesh gave no usable inertia (computeMassProperties' rules, GraspIt!'s), so it is the
  // identity per unit mass. Loaders warn where the value is used: graspable bodies and robot
  // links, not obstacles, whose mass properties GraspIt! never computes.
  bool inertiaFallback = false;

  bool isElastic() const { return youngs.has_value(); }
};

// The dynamic state of a body's centre of mass in world coordinates, as GraspIt! stores it:
// q = (position, quaternion w x y z), v = (linear velocity mm/s, angular velocity rad/s).
struct DynamicState {
  Eigen::Matrix<double, 7, 1> q = (Eigen::Matrix<double, 7, 1>() << 0, 0, 0, 1, 0, 0, 0).finished();
  Eigen::Matrix<double, 6, 1> v = Eigen::Matrix<double, 6, 1>::Zero();
};

enum class BodyKind { Obstacle, Graspable };
// "obstacle" and "graspable", the kinds every front end prints and accepts.
std::span<const EnumName<BodyKind>> enumNames(std::type_identity<BodyKind>);

// A body placed in a world: an obstacle (static) or a graspable body (dynamic).
struct Body {
  std::shared_ptr<const BodyModel> model;
  BodyKind kind = BodyKind::Obstacle;
  std::string name;                        // unique within the world
  std::filesystem::path filename;          // as written in the world file (for saving)
  Transform pose = Transform::Identity();  // body frame in world, mm
  DynamicState state;                      // meaningful for graspable bodies

  bool isDynamic() const { return kind == BodyKind::Graspable; }
  // Moves the body and keeps the dynamic state's position (of the CoG) in step.
  void setPose(const Transform& pose);
};

}  // namespace graspkit
