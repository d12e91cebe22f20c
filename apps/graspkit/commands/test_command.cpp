// graspkit test: run Lua scenario tests (*_test.lua) and report per test (see docs/lua.md).

#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>

#include "commands/test_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/lua/junit_report.hpp"
#include "graspkit/lua/test_runner.hpp"
#include "support/progress_reporter.hpp"

namespace graspkit::cli {
namespace {

using lua::TestFailure;
using lua::TestResult;
using lua::TestStatus;
using nlohmann::json;

const char* statusName(TestStatus status) {
  switch (status) {
    case TestStatus::Passed:
      return "passed";
    case TestStatus::Failed:
      return "failed";
    case TestStatus::Skipped:
      return "skipped";
  }
  return "?";
}

// "PASS  file: name (12 ms)"; the whole-file entry has no test name.
std::string resultLine(const std::string& file, const TestResult& test) {
  const char* tag = test.status == TestStatus::Passed   ? "PASS"
                    : test.status == TestStatus::Failed ? "FAIL"
                                                        : "SKIP";
  std::string line = test.wholeFile ? fmt::format("{}  {}", tag, file)
                                    : fmt::format("{}  {}: {}", tag, file, test.name);
  if (test.status == TestStatus::Skipped) {
    if (!test.skipReason.empty()) line += fmt::format(" ({})", test.skipReason);
  } else {
    line += fmt::format(" ({:.0f} ms)", test.seconds * 1000.0);
  }
  return line;
}

// Each failure's lines indented under the test's line (tracebacks' tabs as two spaces).
void printFailures(const TestResult& test, std::ostream& out) {
  for (const TestFailure& failure : test.failures) {
    std::istringstream lines(failure.text());
    for (std::string line; std::getline(lines, line);) {
      std::size_t tabs = 0;
      while (tabs < line.size() && line[tabs] == '\t') ++tabs;
      out << "    " << std::string(2 * tabs, ' ') << line.substr(tabs) << "\n";
    }
  }
}

std::string closingLine(const lua::TestReport& report) {
  std::string line = fmt::format("{} passed, {} failed", report.count(TestStatus::Passed),
                                 report.count(TestStatus::Failed));
  if (const int skipped = report.count(TestStatus::Skipped); skipped > 0) {
    line += fmt::format(", {} skipped", skipped);
  }
  return line;
}

json failureJson(const TestFailure& failure) {
  if (failure.kind == TestFailure::Kind::Expectation) {
    return {{"kind", "expectation"},
            {"file", failure.file},
            {"line", failure.line},
            {"message", failure.message}};
  }
  return {{"kind", "error"}, {"message", failure.message}, {"traceback", failure.traceback}};
}

json reportJson(const lua::TestReport& report) {
  json files = json::array();
  for (const lua::TestFileResult& file : report.files) {
    json tests = json::array();
    for (const TestResult& test : file.tests) {
      json t = {{"name", test.name},
                {"whole_file", test.wholeFile},
                {"status", statusName(test.status)},
                {"seconds", test.seconds},
                {"failures", json::array()}};
      for (const TestFailure& failure : test.failures)
        t["failures"].push_back(failureJson(failure));
      if (test.status == TestStatus::Skipped) t["skip_reason"] = test.skipReason;
      tests.push_back(std::move(t));
    }
    files.push_back({{"file", file.file}, {"tests", std::move(tests)}});
  }
  return {{"files", std::move(files)},
          {"passed", report.count(TestStatus::Passed)},
          {"failed", report.count(TestStatus::Failed)},
          {"skipped", report.count(TestStatus::Skipped)}};
}

// A --junit file in a folder that does not exist fails now, not after the tests ran.
void checkReportFolder(const std::filesystem::path& file) {
  if (file.empty()) return;
  const std::filesystem::path folder = std::filesystem::absolute(file).parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw Error(SourceLocation{file.string()}, "--junit: no such folder " + folder.string());
  }
}

}  // namespace

void addTestCommand(CLI::App& app, TestOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "test",
      "Run Lua scenario tests: the *_test.lua files below each folder given, and each file given");
  cmd->add_option("paths", options.paths, "Test files and folders")->required();
  cmd->add_option("--junit", options.junit, "Also write a JUnit XML report to this file");
  cmd->add_flag("--json", options.json, "Print the report as one JSON object");
  addScriptFlags(*cmd, options.flags);
}

int runTest(const TestOptions& options, bool quiet, bool verbose, std::ostream& out) {
  const std::vector<std::filesystem::path> files = lua::findTestFiles(options.paths);
  checkReportFolder(options.junit);

  lua::TestRunOptions run;
  run.script = scriptOptions(options.flags);
  run.script.printToStderr = options.json;
  // In text mode on a terminal the result lines themselves show the progress.
  const bool show_progress = options.json || isatty(STDOUT_FILENO) == 0;
  ProgressReporter progress(ProgressReporter::forStderr(quiet || !show_progress));
  run.script.progress = [&progress](double fraction, const std::string& text) {
    progress.update(fraction, text);
  };
  int done = 0;
  run.onStart = [&](const std::string& file, const std::string& test) {
    progress.update(-1.0, fmt::format("{} done, running {}: {}", done, file, test));
    if (verbose && !options.json) {
      out << fmt::format("RUN   {}: {}", file, test) << std::endl;
    }
  };
  run.onFinish = [&](const std::string& file, const TestResult& test) {
    ++done;
    progress.clear();
    if (options.json || (quiet && test.status != TestStatus::Failed)) return;
    std::fflush(stdout);  // a test's print() goes through C stdio
    out << resultLine(file, test) << "\n";
    printFailures(test, out);
    out.flush();
  };

  const lua::TestReport report = lua::runTests(files, run);
  progress.clear();
  for (const lua::TestFileResult& file : report.files) {
    if (file.tests.empty())
      warn(WarningKind::Script, SourceLocation{file.file}, "defines no tests");
  }
  if (report.total() == 0) {
    std::cerr << "graspkit: error: no tests found in the test files (define them with "
                 "test(name, function))\n";
    return 1;
  }
  if (options.json) {
    out << reportJson(report).dump(2, ' ', false, json::error_handler_t::replace) << "\n";
  } else {
    out << closingLine(report) << "\n";
  }
  if (!options.junit.empty()) lua::writeJunitReport(report, options.junit);
  return report.count(TestStatus::Failed) > 0 ? 1 : 0;
}

}  // namespace graspkit::cli
