// The scenario test runner (graspkit test): finding test files, the semantics of each expect_*
// on cases whose outcome is known by hand, results per test, and the JUnit XML writer.

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <fstream>
#include <string>
#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/lua/junit_report.hpp"
#include "graspkit/lua/test_runner.hpp"
#include "test_paths.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

TestFileResult runSource(const std::string& source, TestRunOptions options = {}) {
  const fs::path file = writeFile(test::scratchDir() / "case_test.lua", source);
  return runTestFile(file, options);
}

TEST(LuaTestRunner, FindsTestFilesRecursivelySortedOnce) {
  const fs::path dir = test::scratchDir();
  writeFile(dir / "b_test.lua", "");
  writeFile(dir / "a" / "z_test.lua", "");
  writeFile(dir / "a" / "helper.lua", "");
  writeFile(dir / "c_test.lua.orig", "");
  fs::create_directories(dir / "d_test.lua");  // a folder with the suffix is searched, not run
  writeFile(dir / "d_test.lua" / "e_test.lua", "");
  const fs::path explicit_file = writeFile(test::scratchDir() / "named.lua", "");

  // The explicit file first; b_test.lua named again through the folder runs once.
  const std::vector<fs::path> files = findTestFiles({explicit_file, dir / "b_test.lua", dir});
  const std::vector<fs::path> expected = {explicit_file, dir / "b_test.lua",
                                          dir / "a" / "z_test.lua",
                                          dir / "d_test.lua" / "e_test.lua"};
  EXPECT_EQ(files, expected);
}

TEST(LuaTestRunner, MissingPathAndNoTestFilesAreErrors) {
  const fs::path dir = test::scratchDir();
  try {
    findTestFiles({dir / "nope_test.lua"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, (dir / "nope_test.lua").string());
    EXPECT_EQ(e.message(), "no such file or folder");
  }
  writeFile(dir / "notes.lua", "");
  EXPECT_THROW(findTestFiles({dir}), Error);
}

// One test per case; each case is a Lua statement whose outcome is known by hand.
struct ExpectCase {
  const char* statement;
  bool holds;
};

TEST(LuaTestRunner, ExpectationSemantics) {
  const std::vector<ExpectCase> cases = {
      {"expect_true(0)", true},  // Lua truth: only nil and false are false
      {"expect_true(false)", false},
      {"expect_false(nil)", true},
      {"expect_false(0)", false},
      {"expect_nil(false)", false},
      {"expect_not_nil(false)", true},
      {"expect_equal({1, 2}, {1, 2})", true},
      {"expect_equal({1, 2}, {1, 2, 3})", false},
      {"expect_equal({1, 2, 3}, {1, 2})", false},
      {"expect_equal({a = {b = {c = 1}}}, {a = {b = {c = 1.0}}})", true},
      {"expect_equal({a = {b = {c = 1}}}, {a = {b = {c = 1 + 1e-15}}})", false},  // exact
      {"expect_equal(setmetatable({1}, {}), {1})", true},  // metatables are not compared
      {"expect_equal(0 / 0, 0 / 0)", false},
      {"expect_equal('1', 1)", false},
      {"expect_not_equal({1}, {1})", false},
      {"expect_near(1, 1.1, 0.1000001)", true},
      {"expect_near(1, 1.1, 0.09)", false},
      {"expect_near({1, {2, 3}}, {1.01, {2, 2.99}}, 0.02)", true},
      {"expect_near({1, {2, 3}}, {1.01, {2, 2.9}}, 0.02)", false},
      {"expect_near({x = 1, name = 'a'}, {x = 1.001, name = 'a'}, 0.01)", true},
      {"expect_near({x = 1, name = 'a'}, {x = 1.001, name = 'b'}, 0.01)", false},
      {"expect_near({1, 2}, {1, 2, 3}, 1)", false},
      {"expect_near(0 / 0, 0 / 0, 1)", false},
      {"expect_near(1, '1', 1)", false},
      {"expect_error(function() error('x.y') end)", true},
      {"expect_error(function() end)", false},
      {"expect_error(function() error('x.y') end, 'x.y')", true},
      {"expect_error(function() error('xzy') end, 'x.y')", false},  // plain text, not a pattern
      {"expect_error(function() error('x.y') end, 'x%.y')", false},
      {"fail()", false},
  };
  std::string source;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    source += "test('" + std::to_string(i) + "', function() " + cases[i].statement + " end)\n";
  }
  const TestFileResult result = runSource(source);
  ASSERT_EQ(result.tests.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TestResult& test = result.tests[i];
    EXPECT_EQ(test.status, cases[i].holds ? TestStatus::Passed : TestStatus::Failed)
        << cases[i].statement;
    if (!cases[i].holds && !test.failures.empty()) {
      // Recorded at the line of the call: case i is on line i + 1.
      EXPECT_EQ(test.failures[0].kind, TestFailure::Kind::Expectation) << cases[i].statement;
      EXPECT_EQ(test.failures[0].line, static_cast<int>(i) + 1) << cases[i].statement;
    }
  }
}

TEST(LuaTestRunner, ResultsPerTest) {
  const TestFileResult result = runSource(
      "test('passes', function() expect_true(true) end)\n"  // 1
      "test('two failures', function()\n"                   // 2
      "  expect_equal(1, 2)\n"                              // 3
      "  expect_equal(3, 4, 'note')\n"                      // 4
      "end)\n"                                              // 5
      "test('raises', function() error('boom') end)\n"      // 6
      "test('skips', function() skip() end)\n");            // 7
  ASSERT_EQ(result.tests.size(), 4u);
  EXPECT_EQ(result.tests[0].status, TestStatus::Passed);
  EXPECT_FALSE(result.tests[0].wholeFile);

  const TestResult& two = result.tests[1];
  EXPECT_EQ(two.name, "two failures");
  ASSERT_EQ(two.failures.size(), 2u);
  EXPECT_EQ(two.failures[0].line, 3);
  EXPECT_EQ(two.failures[0].message, "expect_equal: 1 vs 2");
  EXPECT_EQ(two.failures[1].line, 4);
  EXPECT_EQ(two.failures[1].message, "expect_equal: 3 vs 4: note");
  EXPECT_EQ(two.failures[1].file, result.file);
  EXPECT_EQ(two.failures[1].text(), result.file + ":4: expect_equal: 3 vs 4: note");

  const TestResult& raises = result.tests[2];
  ASSERT_EQ(raises.failures.size(), 1u);
  EXPECT_EQ(raises.failures[0].kind, TestFailure::Kind::Error);
  // Lua shortens a long file name in error messages to its end ("...").
  EXPECT_TRUE(raises.failures[0].message.ends_with("case_test.lua:6: boom"))
      << raises.failures[0].message;
  EXPECT_TRUE(raises.failures[0].traceback.starts_with("stack traceback:"));

  EXPECT_EQ(result.tests[3].status, TestStatus::Skipped);
  EXPECT_EQ(result.tests[3].skipReason, "");
}

TEST(LuaTestRunner, TimeLimitStopsTheTopLevelChunk) {
  TestRunOptions options;
  options.script.timeoutSeconds = 0.2;
  const TestFileResult result =
      runSource("test('never run', function() end)\nwhile true do end\n", options);
  ASSERT_EQ(result.tests.size(), 1u);
  EXPECT_TRUE(result.tests[0].wholeFile);
  EXPECT_EQ(result.tests[0].status, TestStatus::Failed);
  EXPECT_NE(result.tests[0].failures[0].message.find("time limit"), std::string::npos);
}

TEST(LuaTestRunner, CallbacksSeeEachTestInOrder) {
  std::vector<std::string> events;
  TestRunOptions options;
  options.onStart = [&](const std::string&, const std::string& test) {
    events.push_back("start " + test);
  };
  options.onFinish = [&](const std::string&, const TestResult& test) {
    events.push_back("finish " + test.name);
  };
  runSource("test('a', function() end)\ntest('b', function() end)\n", options);
  const std::vector<std::string> expected = {"start a", "finish a", "start b", "finish b"};
  EXPECT_EQ(events, expected);
}

TestReport handMadeReport() {
  TestResult passed{"ok", false, TestStatus::Passed, 0.0125, {}, ""};
  TestResult skipped{"later", false, TestStatus::Skipped, 0, {}, "no robot"};
  TestResult failed{"bad & <odd>", false, TestStatus::Failed, 0.5, {}, ""};
  failed.failures.push_back({TestFailure::Kind::Expectation, "f_test.lua", 7,
                             "expect_equal: \"a\x01\xff\" vs \"b\"", ""});
  failed.failures.push_back({TestFailure::Kind::Error, "", 0, "f_test.lua:9: boom",
                             "stack traceback:\n\tf_test.lua:9: in function"});
  TestReport report;
  report.files.push_back({"f_test.lua", {passed, skipped, failed}});
  report.files.push_back({"g_test.lua", {passed}});
  return report;
}

TEST(JunitReport, CountsAndTextParseBack) {
  const std::string xml = junitReport(handMadeReport());
  tinyxml2::XMLDocument document;
  ASSERT_EQ(document.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;

  const tinyxml2::XMLElement* suites = document.FirstChildElement("testsuites");
  ASSERT_NE(suites, nullptr);
  EXPECT_EQ(suites->IntAttribute("tests"), 4);
  EXPECT_EQ(suites->IntAttribute("failures"), 1);
  EXPECT_EQ(suites->IntAttribute("skipped"), 1);
  EXPECT_STREQ(suites->Attribute("time"), "0.525");  // 0.0125 + 0 + 0.5 + 0.0125

  const tinyxml2::XMLElement* suite = suites->FirstChildElement("testsuite");
  ASSERT_NE(suite, nullptr);
  EXPECT_STREQ(suite->Attribute("name"), "f_test.lua");
  EXPECT_EQ(suite->IntAttribute("tests"), 3);
  const tinyxml2::XMLElement* ok = suite->FirstChildElement("testcase");
  EXPECT_STREQ(ok->Attribute("classname"), "f_test.lua");
  EXPECT_STREQ(ok->Attribute("time"), "0.013");
  EXPECT_EQ(ok->FirstChildElement(), nullptr);
  const tinyxml2::XMLElement* later = ok->NextSiblingElement("testcase");
  EXPECT_STREQ(later->FirstChildElement("skipped")->Attribute("message"), "no robot");
  const tinyxml2::XMLElement* bad = later->NextSiblingElement("testcase");
  EXPECT_STREQ(bad->Attribute("name"), "bad & <odd>");
  const tinyxml2::XMLElement* failure = bad->FirstChildElement("failure");
  ASSERT_NE(failure, nullptr);
  // The control character and the stray byte 0xFF become U+FFFD; both failures are in the text.
  EXPECT_STREQ(failure->Attribute("message"),
               "f_test.lua:7: expect_equal: \"a\xEF\xBF\xBD\xEF\xBF\xBD\" vs \"b\"");
  EXPECT_STREQ(failure->GetText(),
               "f_test.lua:7: expect_equal: \"a\xEF\xBF\xBD\xEF\xBF\xBD\" vs \"b\"\n"
               "f_test.lua:9: boom\nstack traceback:\n\tf_test.lua:9: in function\n");
  EXPECT_STREQ(suite->NextSiblingElement("testsuite")->Attribute("name"), "g_test.lua");
}

TEST(JunitReport, WritesAtomicallyOrNamesTheFile) {
  const fs::path dir = test::scratchDir();
  const fs::path file = dir / "report.xml";
  writeFile(file, "old");
  writeJunitReport(handMadeReport(), file);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, junitReport(handMadeReport()));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

  const fs::path missing = dir / "no" / "report.xml";
  try {
    writeJunitReport(handMadeReport(), missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, missing.string());
  }
}

}  // namespace
}  // namespace graspkit::lua
