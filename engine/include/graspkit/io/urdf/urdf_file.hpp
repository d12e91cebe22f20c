#pragma once
// URDF robots, read through urdfdom, as graspkit robots (a generic Hand).
//
// - The palm is LoadOptions::urdfPalm, else the URDF's root link. Links hung on it by fixed
//   joints are part of it; each movable joint hung on it starts a chain (chains in the order
//   of their first links in the file), which follows the movable joints below (links on fixed
//   joints join the link before). Where the tree branches below a moving joint, each path from
//   the palm to a leaf is a chain; a shared joint is repeated in each (driven by its DOF) and its
//   link belongs to the first.
// - Revolute, continuous (a range of +-pi) and prismatic joints become DH joints: each chain's
//   joint axes are turned into Denavit-Hartenberg frames at the zero joint vector, and each
//   link keeps its URDF frame as a constant Link::frame on its DH frame, so link poses are the
//   URDF's link frames at every joint vector. Floating and planar joints are refused.
// - A link with no geometry and no <inertial> (an empty frame) hung by fixed joints on links
//   that have them takes the frame of the first of those; a joint that carries only empty
//   links gives no link of its own, and the next link takes its joint too (a Universal link:
//   two joints, a Ball: three), as GraspIt!'s links do.
// - Every joint that mimics no other is a DOF; a mimic joint is coupled to its joint's DOF
//   (value = multiplier * DOF + offset, GraspIt!'s `d#*k+c`).
// - Geometry: every <collision> of a link, or its <visual>s where it has none; meshes (STL,
//   OBJ, PLY, COLLADA) at their `scale`, boxes, cylinders and spheres tessellated. `package://`
//   paths are looked up in LoadOptions::packagePaths, then in the folders above the file;
//   other paths are relative to the file's folder. Metres become millimetres, kilograms grams.
// - Mass properties from <inertial>; a link without one gets GraspIt!'s default mass and the
//   inertia of its geometry.
// - Links are rubber (LoadOptions::urdfMaterial; LoadOptions::urdfLinkMaterials per link, a
//   body taking the material of the link it is named after). DOF controllers get maxEffort from the
//   joint's `effort` and GraspIt!'s Barrett gains; each DOF closes towards its upper limit.
//
// Bad input (a cycle, a link with two parents, a missing mesh, a zero axis, a mimic of a
// missing joint, a non-finite number) throws graspkit::Error naming file, line and element.

#include <filesystem>
#include <memory>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Whether `file` is named as a URDF file (.urdf, any case).
bool isUrdfFile(const std::filesystem::path& file);

std::shared_ptr<const RobotModel> loadUrdfFile(const std::filesystem::path& file,
                                               const LoadOptions& options = {});

}  // namespace graspkit
