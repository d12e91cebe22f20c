#include "graspkit/lua/test_runner.hpp"

#include <fmt/format.h>

#include <lua.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "graspkit/base/error.hpp"

namespace graspkit::lua {

// scripting/lua/testing.lua, compiled in by scripting/CMakeLists.txt.
extern const char* const kTestingLua;

namespace {

namespace fs = std::filesystem;

// The chunk name the test library runs under; where() skips its frames.
constexpr const char* kLibraryChunk = "=graspkit.testing";

// where(): the file and line of the innermost Lua function on the stack that is not the test
// library, i.e. the line of the expect_ call in the test file (or in a helper it called).
int callerLocation(lua_State* L) {
  lua_Debug frame;
  for (int level = 1; lua_getstack(L, level, &frame) != 0; ++level) {
    lua_getinfo(L, "Sl", &frame);
    if (frame.currentline <= 0) continue;  // a C function: pcall, or the host
    if (std::strcmp(frame.source, kLibraryChunk) == 0) continue;
    // A file's chunk name is "@name": the whole name, where short_src may be cut.
    lua_pushstring(L, frame.source[0] == '@' ? frame.source + 1 : frame.short_src);
    lua_pushinteger(L, frame.currentline);
    return 2;
  }
  lua_pushstring(L, "?");
  lua_pushinteger(L, 0);
  return 2;
}

std::string readSource(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(SourceLocation{file.string()}, "cannot read the test file");
  std::ostringstream text;
  text << in.rdbuf();
  std::string source = text.str();
  // As luaL_loadfile does: skip a UTF-8 byte order mark, and blank out a first line starting
  // with '#' (a #! line) but keep its newline, so line numbers stay right.
  if (source.starts_with("\xEF\xBB\xBF")) source.erase(0, 3);
  if (source.starts_with("#")) source.erase(0, source.find('\n'));
  return source;
}

std::string displayName(const fs::path& file) {
  return file.lexically_normal().generic_string();
}

// Splits the message protectedCall reports into the error and Lua's traceback.
TestFailure errorFailure(const std::string& message) {
  TestFailure failure;
  failure.kind = TestFailure::Kind::Error;
  const std::size_t traceback = message.find("\nstack traceback:");
  failure.message = message.substr(0, traceback);
  if (traceback != std::string::npos) failure.traceback = message.substr(traceback + 1);
  return failure;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What the test library recorded for one test (or for the file's top level).
struct Recorded {
  std::vector<TestFailure> failures;
  std::optional<std::string> skipReason;
};

// One test file in its own Lua state, with the test library loaded.
class TestFileRun {
 public:
  TestFileRun(const fs::path& file, const TestRunOptions& options)
      : name_(displayName(file)), host_(file, options.script), L_(host_.state()) {
    loadLibrary();
  }
  TestFileRun(const TestFileRun&) = delete;
  TestFileRun& operator=(const TestFileRun&) = delete;

  const std::string& name() const { return name_; }

  // Runs the file's top level, which registers the tests. Returns the entry for the whole
  // file when it failed or was skipped; the tests run only when it returns nothing or a
  // failure that was just expectations.
  std::optional<TestResult> runTopLevel() {
    const auto start = std::chrono::steady_clock::now();
    callHarness("start", 0, 0);
    const std::string source = readSource(host_.script());
    const std::string chunk = "@" + name_;
    ScriptOutcome outcome;
    if (luaL_loadbufferx(L_, source.data(), source.size(), chunk.c_str(), "t") != LUA_OK) {
      outcome = {false, 1, false, lua_tostring(L_, -1)};
      lua_pop(L_, 1);
    } else {
      outcome = host_.protectedCall(0, 0);
    }
    TestResult result = conclude(name_, outcome, finish(), secondsSince(start));
    result.wholeFile = true;
    stopped_ = !outcome.ok || result.status == TestStatus::Skipped;
    if (result.status == TestStatus::Passed) return std::nullopt;
    return result;
  }

  // Whether the top level ended early (an error or skip()), so the tests are not run.
  bool stopped() const { return stopped_; }

  int testCount() {
    pushTests();
    const auto count = static_cast<int>(lua_rawlen(L_, -1));
    lua_pop(L_, 1);
    return count;
  }

  // The name of test `index` (1-based, in registration order).
  std::string testName(int index) {
    pushTests();
    lua_rawgeti(L_, -1, index);
    lua_getfield(L_, -1, "name");
    std::string name = lua_tostring(L_, -1);
    lua_pop(L_, 3);
    return name;
  }

  TestResult runTest(int index) {
    const std::string name = testName(index);
    const auto start = std::chrono::steady_clock::now();
    lua_pushstring(L_, name.c_str());
    callHarness("start", 1, 0);
    pushTests();
    lua_rawgeti(L_, -1, index);
    lua_getfield(L_, -1, "fn");
    lua_replace(L_, -3);
    lua_pop(L_, 1);
    const ScriptOutcome outcome = host_.protectedCall(0, 0);
    return conclude(name, outcome, finish(), secondsSince(start));
  }

 private:
  void loadLibrary() {
    if (luaL_loadbufferx(L_, kTestingLua, std::strlen(kTestingLua), kLibraryChunk, "t") != LUA_OK) {
      const std::string message = lua_tostring(L_, -1);
      lua_pop(L_, 1);
      throw std::logic_error("the test library does not load: " + message);
    }
    lua_pushcfunction(L_, callerLocation);
    const ScriptOutcome outcome = host_.protectedCall(1, 1);
    if (!outcome.ok) throw std::logic_error("the test library failed: " + outcome.message);
    harness_ = luaL_ref(L_, LUA_REGISTRYINDEX);
  }

  // Calls harness[function] with the `nargs` arguments on the stack. The harness's functions
  // only fail when memory runs out.
  void callHarness(const char* function, int nargs, int nresults) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, harness_);
    lua_getfield(L_, -1, function);
    lua_remove(L_, -2);
    lua_insert(L_, -(nargs + 1));
    if (lua_pcall(L_, nargs, nresults, 0) != LUA_OK) {
      const std::string message = lua_tostring(L_, -1);
      lua_pop(L_, 1);
      throw std::runtime_error(fmt::format("test library: harness.{}: {}", function, message));
    }
  }

  void pushTests() {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, harness_);
    lua_getfield(L_, -1, "tests");
    lua_remove(L_, -2);
  }

  std::string stringField(int table, const char* key) {
    lua_getfield(L_, table, key);
    const char* text = lua_tostring(L_, -1);
    std::string value = text != nullptr ? text : "";
    lua_pop(L_, 1);
    return value;
  }

  Recorded finish() {
    callHarness("finish", 0, 2);
    Recorded recorded;
    if (lua_type(L_, -1) == LUA_TSTRING) recorded.skipReason = lua_tostring(L_, -1);
    const auto count = static_cast<lua_Integer>(lua_rawlen(L_, -2));
    for (lua_Integer i = 1; i <= count; ++i) {
      lua_rawgeti(L_, -2, i);
      TestFailure failure;
      failure.file = stringField(-1, "file");
      failure.message = stringField(-1, "message");
      lua_getfield(L_, -1, "line");
      failure.line = static_cast<int>(lua_tointeger(L_, -1));
      lua_pop(L_, 2);
      recorded.failures.push_back(std::move(failure));
    }
    lua_pop(L_, 2);
    return recorded;
  }

  // A test's result from how its call ended and what it recorded. Failures recorded before a
  // skip() still fail the test, as in GoogleTest.
  static TestResult conclude(const std::string& name, const ScriptOutcome& outcome,
                             Recorded recorded, double seconds) {
    TestResult result;
    result.name = name;
    result.seconds = seconds;
    result.failures = std::move(recorded.failures);
    // The error skip() raises to stop the test is not a failure.
    if (!outcome.ok && !recorded.skipReason)
      result.failures.push_back(errorFailure(outcome.message));
    if (!result.failures.empty()) {
      result.status = TestStatus::Failed;
    } else if (recorded.skipReason) {
      result.status = TestStatus::Skipped;
      result.skipReason = *recorded.skipReason;
    }
    return result;
  }

  std::string name_;
  ScriptHost host_;
  lua_State* L_;
  int harness_ = LUA_NOREF;
  bool stopped_ = false;
};

TestResult wholeFileError(const fs::path& file, const std::string& message) {
  TestResult result;
  result.name = displayName(file);
  result.wholeFile = true;
  result.status = TestStatus::Failed;
  result.failures.push_back(errorFailure(message));
  return result;
}

}  // namespace

std::string TestFailure::text() const {
  if (kind == Kind::Expectation) return fmt::format("{}:{}: {}", file, line, message);
  return traceback.empty() ? message : message + "\n" + traceback;
}

int TestReport::count(TestStatus status) const {
  int n = 0;
  for (const TestFileResult& file : files) {
    n += static_cast<int>(std::count_if(file.tests.begin(), file.tests.end(),
                                        [&](const TestResult& t) { return t.status == status; }));
  }
  return n;
}

int TestReport::total() const {
  int n = 0;
  for (const TestFileResult& file : files) n += static_cast<int>(file.tests.size());
  return n;
}

double TestReport::seconds() const {
  double sum = 0;
  for (const TestFileResult& file : files) {
    for (const TestResult& test : file.tests) sum += test.seconds;
  }
  return sum;
}

std::vector<fs::path> findTestFiles(const std::vector<fs::path>& paths) {
  std::vector<fs::path> files;
  std::set<fs::path> seen;  // canonical, so a file named twice runs once
  auto add = [&](const fs::path& file) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(fs::absolute(file), ec);
    if (seen.insert(ec ? file : canonical).second) files.push_back(file);
  };
  for (const fs::path& path : paths) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(SourceLocation{path.string()}, "no such file or folder");
    if (!fs::is_directory(status)) {
      add(path);
      continue;
    }
    std::vector<fs::path> found;
    for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.ends_with("_test.lua") && it->is_regular_file(ec)) found.push_back(it->path());
    }
    if (ec) throw Error(SourceLocation{path.string()}, "cannot search the folder: " + ec.message());
    std::sort(found.begin(), found.end());
    for (const fs::path& file : found) add(file);
  }
  if (files.empty()) {
    std::string names;
    for (const fs::path& path : paths) names += (names.empty() ? "" : ", ") + path.string();
    throw Error(fmt::format("no test files (*_test.lua) found in {}", names));
  }
  return files;
}

TestFileResult runTestFile(const fs::path& file, const TestRunOptions& options) {
  TestFileResult result;
  result.file = displayName(file);
  auto report = [&](TestResult test) {
    if (options.onFinish) options.onFinish(result.file, test);
    result.tests.push_back(std::move(test));
  };
  std::optional<TestFileRun> run;
  std::optional<TestResult> top;
  try {
    run.emplace(file, options);
    top = run->runTopLevel();
  } catch (const Error& e) {  // the file vanished or cannot be read
    report(wholeFileError(file, e.what()));
    return result;
  }
  if (top) report(std::move(*top));
  if (run->stopped()) return result;
  const int count = run->testCount();
  for (int index = 1; index <= count; ++index) {
    if (options.onStart) options.onStart(result.file, run->testName(index));
    report(run->runTest(index));
  }
  return result;
}

TestReport runTests(const std::vector<fs::path>& files, const TestRunOptions& options) {
  TestReport report;
  for (const fs::path& file : files) report.files.push_back(runTestFile(file, options));
  return report;
}

}  // namespace graspkit::lua
