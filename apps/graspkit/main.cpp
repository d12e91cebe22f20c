// graspkit: the command-line program. Each subcommand lives in its own file (*_command.cpp)
// and registers itself here.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "commands/batch_command.hpp"
#include "commands/convert_command.hpp"
#include "commands/export_command.hpp"
#include "commands/grasp_command.hpp"
#include "commands/info_command.hpp"
#include "commands/objects_command.hpp"
#include "commands/plan_command.hpp"
#include "commands/plugins_command.hpp"
#include "commands/render_command.hpp"
#include "commands/run_command.hpp"
#include "commands/serve_command.hpp"
#include "commands/simulate_command.hpp"
#include "commands/test_command.hpp"
#include "commands/validate_command.hpp"
#include "commands/view_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/base/version.hpp"
#include "support/terminal_text.hpp"
#include "support/warning_reporter.hpp"

namespace {

// What every exit status means; --help prints it, the README repeats it.
constexpr const char* kExitStatuses =
    "Exit status:\n"
    "  0    success\n"
    "  1    failure: bad input (the message names file, line and element), a failed save, a\n"
    "       failing test, a plugin that does not load, a Lua error\n"
    "  2    usage: an unknown option, a missing or invalid argument, a file named on the\n"
    "       command line that does not exist\n"
    "  3    internal error (a bug: please report it)\n"
    "  124  a script stopped by --timeout\n"
    "  run: a script's os.exit(n) exits with n";

constexpr int kUsageStatus = 2;
constexpr int kInternalStatus = 3;

// CLI11's own messages are kept; they get the program's prefix and its exit status for usage
// errors (CLI11 would exit with its internal codes, 105-109).
int usageError(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  std::cerr << "graspkit: error: " << e.what() << "\n"
            << "Run 'graspkit --help' or 'graspkit COMMAND --help' for the usage.\n";
  return kUsageStatus;
}

// The first word of the command line that is not an option (nor the value of --no-warn), when it
// names no command: `graspkit frobnicate` is an unknown command, not a missing one.
std::optional<std::string> unknownCommand(const CLI::App& app, int argc, char** argv) {
  if (!app.get_subcommands().empty()) return std::nullopt;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") return std::nullopt;
    if (arg == "--no-warn") {
      ++i;
      continue;
    }
    if (arg.starts_with("-")) continue;
    for (const CLI::App* command : app.get_subcommands({}))
      if (command->check_name(std::string(arg))) return std::nullopt;
    return std::string(arg);
  }
  return std::nullopt;
}

// The commands, as `graspkit --help` lists them: "info, grasp, plan, ...".
std::string commandNames(const CLI::App& app) {
  std::string names;
  for (const CLI::App* command : app.get_subcommands({}))
    names.append(names.empty() ? "" : ", ").append(command->get_name());
  return names;
}

// Each subcommand's options, filled by the parser.
struct CommandOptions {
  graspkit::cli::InfoOptions info;
  graspkit::cli::GraspOptions grasp;
  graspkit::cli::PluginsOptions plugins;
  graspkit::cli::RunOptions run;
  graspkit::cli::TestOptions test;
  graspkit::cli::PlanOptions plan;
  graspkit::cli::ConvertOptions convert;
  graspkit::cli::RenderOptions render;
  graspkit::cli::ExportOptions exportScene;
  graspkit::cli::ViewOptions view;
  graspkit::cli::ServeOptions serve;
  graspkit::cli::SimulateOptions simulate;
  graspkit::cli::ValidateOptions validate;
  graspkit::cli::ObjectsOptions objects;
  graspkit::cli::BatchOptions batch;
};

int runCommand(const CLI::App& app, const CommandOptions& o, bool quiet, bool verbose) {
  using namespace graspkit::cli;
  try {
    if (app.got_subcommand("info")) return runInfo(o.info, std::cout);
    if (app.got_subcommand("grasp")) return runGrasp(o.grasp, std::cout);
    if (app.got_subcommand("plugins")) return runPlugins(o.plugins, std::cout);
    if (app.got_subcommand("run")) return runRun(o.run, quiet);
    if (app.got_subcommand("test")) return runTest(o.test, quiet, verbose, std::cout);
    if (app.got_subcommand("plan")) return runPlan(o.plan, quiet, std::cout);
    if (app.got_subcommand("convert")) return runConvert(o.convert, quiet, std::cout);
    if (app.got_subcommand("render")) return runRender(o.render, std::cout);
    if (app.got_subcommand("export")) return runExport(o.exportScene, std::cout);
    if (app.got_subcommand("view")) return runView(o.view, std::cout);
    if (app.got_subcommand("serve")) return runServe(o.serve, std::cout);
    if (app.got_subcommand("simulate")) return runSimulate(o.simulate, std::cout);
    if (app.got_subcommand("validate")) return runValidate(o.validate, std::cout);
    if (app.got_subcommand("objects")) return runObjects(o.objects, quiet, std::cout);
    if (app.got_subcommand("batch")) return runBatch(o.batch, quiet, std::cout);
  } catch (const graspkit::Error& e) {
    std::cerr << "graspkit: error: " << e.what() << "\n";
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    // The file system refused something (a loop of symbolic links, no permission): the user's
    // setup, not a bug. Readers turn the ones they expect into located errors first.
    std::cerr << "graspkit: error: " << e.path1().string() << ": " << e.code().message() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "graspkit: internal error: " << e.what() << "\n";
    return kInternalStatus;
  } catch (...) {
    std::cerr << "graspkit: internal error: an exception that is not a std::exception (from a "
                 "plugin's code?)\n";
    return kInternalStatus;
  }
  return 0;
}

std::set<graspkit::WarningKind> silencedKinds(const std::vector<std::string>& names) {
  std::set<graspkit::WarningKind> kinds;
  for (const std::string& name : names)
    kinds.insert(*graspkit::valueNamed<graspkit::WarningKind>(name));
  return kinds;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"graspkit: a grasp simulator that reads GraspIt! files"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("graspkit ") + graspkit::engineVersion(),
                       "Print the version and exit");
  app.footer(kExitStatuses);
  app.fallthrough();  // --quiet, --verbose and --no-warn also after the subcommand
  bool quiet = false;
  bool verbose = false;
  std::vector<std::string> no_warn;
  app.add_flag("-q,--quiet", quiet, "Print errors only");
  app.add_flag("-v,--verbose", verbose, "Print debugging detail and every repeated warning");
  std::vector<std::string> kind_names;
  for (graspkit::WarningKind kind : graspkit::kWarningKinds)
    kind_names.emplace_back(graspkit::nameOf(kind));
  app.add_option("--no-warn", no_warn, "Hide one kind of warning (repeatable)")
      ->check(CLI::IsMember(kind_names))
      ->type_name("KIND");

  CommandOptions options;
  graspkit::cli::addInfoCommand(app, options.info);
  graspkit::cli::addGraspCommand(app, options.grasp);
  graspkit::cli::addPluginsCommand(app, options.plugins);
  graspkit::cli::addRunCommand(app, options.run);
  graspkit::cli::addTestCommand(app, options.test);
  graspkit::cli::addPlanCommand(app, options.plan);
  graspkit::cli::addConvertCommand(app, options.convert);
  graspkit::cli::addRenderCommand(app, options.render);
  graspkit::cli::addExportCommand(app, options.exportScene);
  graspkit::cli::addViewCommand(app, options.view);
  graspkit::cli::addServeCommand(app, options.serve);
  graspkit::cli::addSimulateCommand(app, options.simulate);
  graspkit::cli::addValidateCommand(app, options.validate);
  graspkit::cli::addObjectsCommand(app, options.objects);
  graspkit::cli::addBatchCommand(app, options.batch);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != 0) {
      if (const auto unknown = unknownCommand(app, argc, argv)) {
        std::cerr << "graspkit: error: unknown command '" << graspkit::cli::terminalSafe(*unknown)
                  << "'\n"
                  << "The commands are: " << commandNames(app) << ".\n"
                  << "Run 'graspkit --help' or 'graspkit COMMAND --help' for the usage.\n";
        return kUsageStatus;
      }
    }
    return usageError(app, e);
  }
  // Errors, warnings and traces go to stderr, so --json output on stdout stays parseable.
  spdlog::set_default_logger(spdlog::stderr_color_mt("graspkit"));
  spdlog::set_level(quiet     ? spdlog::level::err
                    : verbose ? spdlog::level::debug
                              : spdlog::level::warn);
  spdlog::set_pattern("graspkit: %l: %v");
  graspkit::cli::WarningReporter warnings(
      {.quiet = quiet, .silenced = silencedKinds(no_warn), .shownRepeats = verbose ? 0 : 3},
      std::cerr);
  graspkit::setWarningHandler([&warnings](const graspkit::Warning& w) { warnings.report(w); });
  int status = 0;
  {
    const bool scripted = app.got_subcommand("run") || app.got_subcommand("test");
    const graspkit::cli::TerminalSafeStreams safe_streams(!scripted);
    status = runCommand(app, options, quiet, verbose);
    graspkit::setWarningHandler({});
    warnings.summarize();
  }
  // Output that never reached its reader (a full disk, a closed pipe) is a failure, not a 0.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "graspkit: error: cannot write standard output: " << std::strerror(errno) << "\n";
    return 1;
  }
  return status;
}
