#pragma once
// A test report as JUnit XML, the format CI services read: <testsuites> holding one
// <testsuite> per test file, one <testcase> per test (classname = the file), a <failure> with
// every failure's text, or <skipped>.

#include <filesystem>
#include <string>

#include "graspkit/lua/test_runner.hpp"

namespace graspkit::lua {

std::string junitReport(const TestReport& report);

// Writes junitReport(report) to `file` atomically (a temporary beside it, then a rename), so a
// reader never sees half a report. Throws graspkit::Error naming the file when it cannot.
void writeJunitReport(const TestReport& report, const std::filesystem::path& file);

}  // namespace graspkit::lua
