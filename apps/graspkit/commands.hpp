#pragma once
// The subcommands of the graspkit program.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "load_flags.hpp"

#include "graspkit/transform.hpp"
#include "script_flags.hpp"

namespace graspkit {
class World;
}

namespace graspkit::cli {

// The check of a file argument: "no such file: NAME" or "NAME is a folder, not a file".
CLI::Validator existingFile();
CLI::Validator seedNumber();      // 0 .. 2^64 - 1, digits only
CLI::Validator positiveFinite();  // > 0 and finite

struct InfoOptions {
  std::filesystem::path file;
  LoadFlags load;
  std::string dofs;   // comma-separated DOF values
  std::string robot;  // name or 0-based index; the first robot when empty
  bool json = false;
};

void addInfoCommand(CLI::App& app, InfoOptions& options);
int runInfo(const InfoOptions& options, std::ostream& out);

struct GraspOptions {
  std::filesystem::path world;
  LoadFlags load;
  std::string robot;   // name or 0-based index; the world's first hand when empty
  std::string object;  // body name; the first graspable body when empty
  std::string pose;    // tx,ty,tz,qw,qx,qy,qz (mm, world)
  std::string dofs;    // comma-separated DOF values
  bool autograsp = false;
  std::string gws = "L1";
  bool json = false;
};

void addGraspCommand(CLI::App& app, GraspOptions& options);
// --robot names a robot by its name or its 0-based index (as the JSON lists robots and the C ABI
// counts them; Lua counts from 1, as Lua does). Throws graspkit::Error naming the world's robots
// when there is no such robot.
int robotByNameOrIndex(const World& world, const std::string& robot);
// The robot grasp and plan work on: --robot when given, else the world's first hand, as
// GraspIt! picks its current hand. Throws graspkit::Error when there is none.
int chooseHand(const World& world, const std::string& robot);
int runGrasp(const GraspOptions& options, std::ostream& out);

struct PluginsOptions {
  bool json = false;
};

void addPluginsCommand(CLI::App& app, PluginsOptions& options);
// Lists every plugin on the search path and what it provides. Exit status 1 when a plugin on the
// path failed to load (each failure is listed with its reason).
int runPlugins(const PluginsOptions& options, std::ostream& out);

struct RunOptions {
  std::filesystem::path script;
  std::vector<std::string> args;
  bool json = false;  // print the script's return value as JSON
  ScriptFlags flags;
};

void addRunCommand(CLI::App& app, RunOptions& options);
// Exit status: 0, the script's os.exit status, 1 after a Lua error (traceback on stderr), 124
// after --timeout.
int runRun(const RunOptions& options, bool quiet);

struct TestOptions {
  std::vector<std::filesystem::path> paths;  // test files and folders
  std::filesystem::path junit;               // --junit FILE; none when empty
  bool json = false;
  ScriptFlags flags;
};

void addTestCommand(CLI::App& app, TestOptions& options);
// Prints a line per test and "N passed, N failed[, N skipped]" (or one JSON object). Exit
// status 0 when no test failed, 1 when one did or no test was found.
int runTest(const TestOptions& options, bool quiet, bool verbose, std::ostream& out);

struct ConvertOptions {
  std::filesystem::path input;
  std::filesystem::path out;  // beside the input, .xml, when empty; a folder with --to
  std::string to;             // robots: the format to write (urdf, mjcf)
  LoadFlags load;             // robots: how to read the input
  bool force = false;
  std::string material = "plastic";
  double mass = 300.0;
  double scale = 1.0;
};

void addConvertCommand(CLI::App& app, ConvertOptions& options);
// Writes the conversion atomically; a target that exists and differs needs --force.
int runConvert(const ConvertOptions& options, bool quiet, std::ostream& out);

struct PlanOptions {
  std::filesystem::path world;
  LoadFlags load;
  std::string robot;   // name or 0-based index; the world's first hand when empty
  std::string object;  // the first graspable body when empty
  std::string planner = "simann";
  std::string energy = "contact";
  std::string space = "axis-angle";
  std::string posture = "eigen";
  std::string mode = "restarts";
  std::string preset;            // the planner's default when empty
  std::vector<std::string> set;  // KEY=VALUE planner options
  std::optional<std::int64_t> steps;
  std::optional<double> seconds;
  std::optional<int> threads;  // every core when unset
  std::uint64_t seed = 1;
  int top = 20;
  bool validate = false;  // label each grasp physically (graspkit validate)
  double validateSeconds = 2.0;
  bool json = false;
  std::filesystem::path out;
};

void addPlanCommand(CLI::App& app, PlanOptions& options);
// Prints the best grasps as a table (or JSON); with --out also writes the JSON and one world
// file per grasp. Progress goes to stderr: a redrawn line with percentage and ETA on a
// terminal, a plain line every few seconds otherwise (unless quiet).
int runPlan(const PlanOptions& options, bool quiet, std::ostream& out);

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
  bool noLabels = false;  // plans: no "#rank eps vol" in the tiles' corners
};

void addRenderCommand(CLI::App& app, RenderOptions& options);
// Writes the PNG atomically: one view of a world, a grasp, or a contact sheet of a plan's grasps
// (rank order by rows).
int runRender(const RenderOptions& options, std::ostream& out);

struct ExportOptions {
  std::filesystem::path input;
  std::filesystem::path gltf;
  LoadFlags load;
  int grasp = 0;
  int top = 0;
};

void addExportCommand(CLI::App& app, ExportOptions& options);
// Writes a binary glTF (.glb): one scene for a world, one per grasp for a plan.
int runExport(const ExportOptions& options, std::ostream& out);

struct ViewOptions {
  std::filesystem::path input;
  std::filesystem::path html;
  LoadFlags load;
  int top = 0;
};

void addViewCommand(CLI::App& app, ViewOptions& options);
// Writes one self-contained HTML page (three.js inside): orbit the scene, step through grasps.
int runView(const ViewOptions& options, std::ostream& out);

struct SimulateOptions {
  std::filesystem::path world;
  LoadFlags load;
  double seconds = 1.0;
  double dt = 0.0025;
  std::string gravity;  // "X,Y,Z" or "off"; the world's default when empty
  bool autograsp = false;
  std::filesystem::path trajectory;
  int every = 10;
  std::filesystem::path out;
  bool json = false;
};

void addSimulateCommand(CLI::App& app, SimulateOptions& options);
// Steps the world; exit 1 when the simulation stopped on a bad state (the report says why).
int runSimulate(const SimulateOptions& options, std::ostream& out);
// "X,Y,Z" (mm/s^2) or "off"; throws graspkit::Error naming --gravity otherwise.
Vector3 parseGravity(const std::string& text);

struct ValidateOptions {
  std::filesystem::path input;
  LoadFlags load;
  int grasp = 0;
  int top = 0;
  double seconds = 2.0;
  std::optional<int> threads;  // every core when unset
  bool json = false;
};

void addValidateCommand(CLI::App& app, ValidateOptions& options);
int runValidate(const ValidateOptions& options, std::ostream& out);

struct ObjectsOptions {
  std::size_t generate = 0;  // how many objects
  std::uint64_t seed = 1;
  std::filesystem::path out;
  double minSize = 40.0;  // mm
  double maxSize = 120.0;
  double density = 0.5;  // g/cm^3
  std::string material = "plastic";
  std::vector<std::string> kinds;  // empty: every kind
  bool force = false;
};

void addObjectsCommand(CLI::App& app, ObjectsOptions& options);
// Writes every object's OFF mesh and Body XML into the folder, and objects.txt listing the XMLs.
// A file that exists and differs needs --force; without it nothing is written.
int runObjects(const ObjectsOptions& options, bool quiet, std::ostream& out);

struct BatchOptions {
  std::filesystem::path hand;
  std::filesystem::path objects;  // a folder of body files or a list file
  std::filesystem::path out;
  LoadFlags load;
  int grasps = 20;
  std::int64_t steps = 40000;
  std::optional<double> secondsPerObject;
  bool validate = false;
  double validateSeconds = 2.0;
  std::uint64_t seed = 1;
  std::string shard;  // K/N
  double objectTimeout = 1800.0;
};

void addBatchCommand(CLI::App& app, BatchOptions& options);
// Exit status 1 when some object of the share failed (after its retry), 0 otherwise.
int runBatch(const BatchOptions& options, bool quiet, std::ostream& out);

// "1,2.5,-3" -> {1, 2.5, -3}; throws graspkit::Error naming `option` for anything else
// (empty items, trailing text, NaN or infinity).
std::vector<double> parseNumberList(const std::string& text, const std::string& option);

}  // namespace graspkit::cli
