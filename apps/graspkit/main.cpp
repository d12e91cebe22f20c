// graspkit: the command-line program. Each subcommand lives in its own file (*_command.cpp)
// and registers itself here.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "graspkit/error.hpp"
#include "graspkit/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"graspkit: a grasp simulator that reads GraspIt! files"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("graspkit ") + graspkit::engineVersion(),
                       "Print the version and exit");
  app.fallthrough();  // --quiet and --verbose also after the subcommand
  bool quiet = false;
  bool verbose = false;
  app.add_flag("-q,--quiet", quiet, "Print errors only");
  app.add_flag("-v,--verbose", verbose, "Print debugging detail");

  graspkit::cli::InfoOptions info;
  graspkit::cli::addInfoCommand(app, info);
  graspkit::cli::GraspOptions grasp;
  graspkit::cli::addGraspCommand(app, grasp);
  graspkit::cli::PluginsOptions plugins;
  graspkit::cli::addPluginsCommand(app, plugins);
  graspkit::cli::RunOptions run;
  graspkit::cli::addRunCommand(app, run);
  graspkit::cli::TestOptions test;
  graspkit::cli::addTestCommand(app, test);
  graspkit::cli::PlanOptions plan;
  graspkit::cli::addPlanCommand(app, plan);
  graspkit::cli::ConvertOptions convert;
  graspkit::cli::addConvertCommand(app, convert);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  // Warnings and errors go to stderr, so --json output on stdout stays parseable.
  spdlog::set_default_logger(spdlog::stderr_color_mt("graspkit"));
  spdlog::set_level(quiet     ? spdlog::level::err
                    : verbose ? spdlog::level::debug
                              : spdlog::level::warn);
  spdlog::set_pattern("graspkit: %l: %v");
  int status = 0;
  try {
    if (app.got_subcommand("info")) status = graspkit::cli::runInfo(info, std::cout);
    if (app.got_subcommand("grasp")) status = graspkit::cli::runGrasp(grasp, std::cout);
    if (app.got_subcommand("plugins")) status = graspkit::cli::runPlugins(plugins, std::cout);
    if (app.got_subcommand("run")) status = graspkit::cli::runRun(run, quiet);
    if (app.got_subcommand("test"))
      status = graspkit::cli::runTest(test, quiet, verbose, std::cout);
    if (app.got_subcommand("plan")) status = graspkit::cli::runPlan(plan, quiet, std::cout);
    if (app.got_subcommand("convert"))
      status = graspkit::cli::runConvert(convert, quiet, std::cout);
  } catch (const graspkit::Error& e) {
    std::cerr << "graspkit: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "graspkit: internal error: " << e.what() << "\n";
    return 2;
  } catch (...) {
    std::cerr << "graspkit: internal error: an exception that is not a std::exception (from a "
                 "plugin's code?)\n";
    return 2;
  }
  // Output that never reached its reader (a full disk, a closed pipe) is a failure, not a 0.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "graspkit: error: cannot write standard output: " << std::strerror(errno) << "\n";
    return 1;
  }
  return status;
}
