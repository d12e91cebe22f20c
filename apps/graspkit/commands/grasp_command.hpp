#pragma once
// graspkit grasp: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct GraspOptions {
  std::filesystem::path world;
  LoadFlags load;
  std::string robot;   // name or 0-based index; the world's first hand when empty
  std::string object;  // body name; the first graspable body when empty
  std::string pose;    // tx,ty,tz,qw,qx,qy,qz (mm, world)
  std::string dofs;    // comma-separated DOF values
  bool autograsp = false;
  std::string gws;  // default: GraspRequest's, set by addGraspCommand
  bool json = false;
};

void addGraspCommand(CLI::App& app, GraspOptions& options);
int runGrasp(const GraspOptions& options, std::ostream& out);

}  // namespace graspkit::cli
