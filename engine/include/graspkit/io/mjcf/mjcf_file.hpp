#pragma once
// Robots read from MJCF (MuJoCo Menagerie's hands), and any robot written as MJCF so that
// MuJoCo can load GraspIt!'s hands (and act as a second method for their dynamics).

#include <filesystem>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Whether `file` is an MJCF file: named .xml or .mjcf with a <mujoco> root element.
bool isMjcfFile(const std::filesystem::path& file);

// Reads an MJCF model as a hand (docs/hands.md, "MJCF"): <include>, <compiler> (angle, meshdir,
// assetdir, eulerseq, autolimits), <default> classes with class/childclass, the body tree with
// pos/quat/axisangle/euler/xyaxes/zaxis and <frame>, hinge and slide joints (a free, ball or any
// joint of a top-level body moves the hand in the world and is left out, with a warning),
// collision geoms (mesh with scale/refpos/refquat, box, sphere, capsule, cylinder, ellipsoid,
// fromto; contype = conaffinity = 0 is visual only), <inertial> or geom mass, one DOF per
// actuator (joint or fixed tendon; none: one per joint), joint equalities with linear polycoef,
// connect loops closed by a linear coupling fitted to the solved loop, and <contact><exclude>.
// Bodies fixed to the world form the palm. Errors name file, line and element.
std::shared_ptr<const RobotModel> loadMjcfFile(const std::filesystem::path& file,
                                               const LoadOptions& options = {});

}  // namespace graspkit
