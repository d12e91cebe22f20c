#pragma once
// graspkit render: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct RenderOptions {
  std::filesystem::path input;  // a world XML or a plan JSON
  std::filesystem::path out;
  LoadFlags load;
  std::string size = "640x480";
  std::string camera = "auto";
  bool contacts = false;
  int grasp = 0;  // 1-based; 0: every grasp (up to --top)
  int top = 20;
  int columns = 0;
  int samples = 1;
  bool noLabels = false;      // plans: no "#rank eps vol" in the tiles' corners
  bool noFloor = false;       // no floor and no shadows
  std::string hand = "auto";  // solid, outline, transparent; auto: outline for grasps
  bool fileColours = false;   // keep a hand's colour even when it is alike the object's
};

void addRenderCommand(CLI::App& app, RenderOptions& options);
// Writes the PNG atomically: one view of a world, a grasp, or a contact sheet of a plan's grasps
// (rank order by rows).
int runRender(const RenderOptions& options, std::ostream& out);

}  // namespace graspkit::cli
