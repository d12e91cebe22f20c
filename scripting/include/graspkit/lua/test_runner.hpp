#pragma once
// Scenario tests: Lua files named *_test.lua that register tests with test(name, fn) and check
// with expect_* (the library in scripting/lua/testing.lua). `graspkit test` finds the files,
// runs each in its own ScriptHost (so no file sees another's globals) and reports per test.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "graspkit/lua/script_host.hpp"

namespace graspkit::lua {

// One reason a test failed.
struct TestFailure {
  enum class Kind {
    Expectation,  // an expect_* (or fail()) that did not hold; the test went on
    Error,        // an error raised in the test (or while loading the file); the test stopped
  };
  Kind kind = Kind::Expectation;
  std::string file;  // expectations: the file of the expect_ call ("" for errors)
  int line = 0;      // expectations: its line (0 for errors)
  std::string message;
  std::string traceback;  // errors: Lua's stack traceback ("" when there is none)

  // "file:line: message" for an expectation; the message and its traceback for an error.
  std::string text() const;
};

enum class TestStatus { Passed, Failed, Skipped };

struct TestResult {
  std::string name;
  // True for the entry that stands for the file's top level: a file that fails to load, raises
  // or fails an expectation outside any test, or calls skip() at the top level.
  bool wholeFile = false;
  TestStatus status = TestStatus::Passed;
  double seconds = 0;
  std::vector<TestFailure> failures;  // empty unless Failed
  std::string skipReason;             // Skipped: the reason given to skip() (may be empty)
};

struct TestFileResult {
  std::string file;  // the file's name as found (a PATH argument, or below one)
  std::vector<TestResult> tests;
};

struct TestReport {
  std::vector<TestFileResult> files;

  int count(TestStatus status) const;
  int total() const;
  double seconds() const;
};

struct TestRunOptions {
  // Sandbox, time limit (per test and per file chunk), model roots, and where print() goes
  // (script.printToStderr keeps a --json report on stdout parseable).
  ScriptOptions script;
  // Called before each test runs and after each result (whole-file entries included).
  std::function<void(const std::string& file, const std::string& test)> onStart;
  std::function<void(const std::string& file, const TestResult& result)> onFinish;
};

// The test files the paths name: a file as given; a folder searched recursively for regular
// files named *_test.lua, in sorted order. Each file once, in the order first named. Throws
// graspkit::Error naming a path that does not exist, and when no test file is found.
std::vector<std::filesystem::path> findTestFiles(const std::vector<std::filesystem::path>& paths);

// Runs one test file in a fresh Lua state: its top-level chunk (which registers the tests),
// then each test in the order registered, each under the time limit.
TestFileResult runTestFile(const std::filesystem::path& file, const TestRunOptions& options);

TestReport runTests(const std::vector<std::filesystem::path>& files, const TestRunOptions& options);

}  // namespace graspkit::lua
