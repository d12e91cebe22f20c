// The scripting sandbox (docs/security.md), attacked the way a hostile or careless script would:
// each way out (running programs, native code, bytecode, files outside the allowed folders by
// absolute path, `..` or symbolic link) must be refused with a message naming the function and the
// file, while the script's own folder, --allow-read, --allow-write and the model roots stay usable.
// Where it is cheap, the same attack under --unsafe shows the attack is real (it succeeds there).
// The time limit must stop loops that catch errors or hide in coroutines.

#include <dlfcn.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <lua.hpp>

#include "graspkit/lua/script_host.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeFile(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// A path as a Lua long-bracket string literal.
std::string lit(const fs::path& path) {
  return "[==[" + path.string() + "]==]";
}

// Runs the test with the current folder changed, restoring it afterwards.
class CurrentFolder {
 public:
  explicit CurrentFolder(const fs::path& folder) : saved_(fs::current_path()) {
    fs::current_path(folder);
  }
  ~CurrentFolder() { fs::current_path(saved_); }

 private:
  fs::path saved_;
};

// A scratch tree:
//   scripts/      the script's folder: main.lua, helper.lua, pkg/sub.lua, own.txt and three
//                 symbolic links leading to outside/ (a folder, a file, a file not yet made)
//   outside/      secret.txt, secretmod.lua: nothing grants access here
//   allow_read/   data.txt        (--allow-read in some tests)
//   allow_write/                  (--allow-write in some tests)
//   models/       hand.xml        (a model root in some tests)
class LuaSandbox : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "graspkit_sandbox_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
    scripts_ = root_ / "scripts";
    outside_ = root_ / "outside";
    allowRead_ = root_ / "allow_read";
    allowWrite_ = root_ / "allow_write";
    models_ = root_ / "models";
    writeFile(scripts_ / "main.lua", "return\n");
    writeFile(scripts_ / "helper.lua", "return { answer = 42 }\n");
    writeFile(scripts_ / "pkg" / "sub.lua", "return 'sub'\n");
    writeFile(scripts_ / "own.txt", "own");
    writeFile(outside_ / "secret.txt", "secret");
    writeFile(outside_ / "secretmod.lua", "return 'leaked'\n");
    writeFile(allowRead_ / "data.txt", "data");
    fs::create_directories(allowWrite_);
    writeFile(models_ / "hand.xml", "<robot/>");
    fs::create_directory_symlink(outside_, scripts_ / "out_dir");
    fs::create_symlink(outside_ / "secret.txt", scripts_ / "out_file");
    fs::create_symlink(outside_ / "created.txt", scripts_ / "dangling");
  }

  void TearDown() override { fs::remove_all(root_); }

  static ScriptOptions sandboxed() {
    ScriptOptions options;
    options.load.useEnvironment = false;  // GRASPKIT_ROOT of the machine must not widen reads
    return options;
  }

  static ScriptOptions unsafe() {
    ScriptOptions options = sandboxed();
    options.sandbox.unsafe = true;
    return options;
  }

  ScriptOutcome run(const std::string& source, const ScriptOptions& options = sandboxed()) {
    ScriptHost host(scripts_ / "main.lua", options);
    return host.runString(source, "attack");
  }

  // The run failed and its message holds each of `words`.
  static void expectRefused(const ScriptOutcome& outcome,
                            std::initializer_list<std::string> words) {
    EXPECT_FALSE(outcome.ok);
    for (const std::string& word : words) {
      EXPECT_NE(outcome.message.find(word), std::string::npos)
          << "'" << word << "' missing from: " << outcome.message;
    }
  }

  static void expectOk(const ScriptOutcome& outcome) { EXPECT_TRUE(outcome.ok) << outcome.message; }

  fs::path root_, scripts_, outside_, allowRead_, allowWrite_, models_;
};

// --- Programs, native code, the debug library ------------------------------------------------

TEST_F(LuaSandbox, DangerousFunctionsAreGone) {
  expectOk(run(R"(
    assert(os.execute == nil, 'os.execute')
    assert(io.popen == nil, 'io.popen')
    assert(package.loadlib == nil, 'package.loadlib')
    assert(debug == nil, 'debug')
    assert(package.loaded.debug == nil, 'package.loaded.debug')
    assert(os.tmpname == nil, 'os.tmpname')
    assert(io.tmpfile == nil, 'io.tmpfile')
    assert(package.cpath == '', 'package.cpath')
    assert(#package.searchers == 2, 'C searchers')
    -- what stays
    assert(os.getenv and os.time and os.clock and os.date and os.exit)
  )"));
  expectOk(run(R"(
    assert(os.execute and io.popen and package.loadlib and debug and os.tmpname and io.tmpfile)
    assert(#package.searchers == 4)
  )",
               unsafe()));
}

TEST_F(LuaSandbox, OsExecuteIsRefused) {
  const fs::path marker = root_ / "executed";
  const std::string attack = fmt::format("os.execute('touch ' .. {})", lit(marker));
  expectRefused(run(attack), {"execute"});
  EXPECT_FALSE(fs::exists(marker));
  expectOk(run(attack, unsafe()));
  EXPECT_TRUE(fs::exists(marker)) << "the attack itself is real";
}

TEST_F(LuaSandbox, IoPopenIsRefused) {
  expectRefused(run("io.popen('echo hello')"), {"popen"});
}

TEST_F(LuaSandbox, PackageLoadlibIsRefused) {
  expectRefused(run("package.loadlib('libc.so.6', '*')"), {"loadlib"});
}

TEST_F(LuaSandbox, DebugLibraryIsRefused) {
  expectRefused(run("debug.sethook()"), {"debug"});
  expectRefused(run("require('debug')"), {"module 'debug' not found"});
}

// A real Lua C module in reach: scripts/utf8-x.so links to the Lua library itself, whose
// luaopen_utf8 require finds through the name's prefix before the hyphen.
TEST_F(LuaSandbox, CModuleIsNotLoaded) {
  Dl_info info{};
  ASSERT_NE(dladdr(reinterpret_cast<void*>(&lua_newstate), &info), 0);
  const fs::path library = fs::absolute(info.dli_fname);
  fs::create_symlink(library, scripts_ / "utf8-x.so");
  const std::string attack = fmt::format(R"(
    package.cpath = {} .. '/?.so'
    local m = require('utf8-x')
    assert(type(m.char) == 'function')
  )",
                                         lit(scripts_));
  const ScriptOutcome refused = run(attack);
  expectRefused(refused, {"module 'utf8-x' not found"});
  EXPECT_EQ(refused.message.find("utf8-x.so"), std::string::npos)
      << "the C searcher looked: " << refused.message;
  if (library.string().find("lua") == std::string::npos) {
    GTEST_SKIP() << "Lua is linked statically; no library to load as a C module";
  }
  expectOk(run(attack, unsafe()));
}

TEST_F(LuaSandbox, BinaryChunksAreRefused) {
  const std::string dump = "local code = string.dump(function() return 7 end)\n";
  expectRefused(run(dump + "assert(load(code))"), {"load", "sandbox", "binary"});
  expectRefused(run(dump + "assert(load(code, 'x', 'b'))"), {"load", "sandbox", "binary"});
  expectRefused(run(dump + R"(
    local given = false
    assert(load(function() if given then return nil end given = true return code end, 'x', 'b'))
  )"),
                {"binary chunk"});
  // The same bytecode in a file beside the script.
  const std::string write_file = dump + fmt::format(
                                            "local f = assert(io.open({}, 'wb')) f:write(code) "
                                            "f:close()\n",
                                            lit(scripts_ / "bytecode.lua"));
  expectRefused(
      run(write_file + fmt::format("assert(loadfile({}))", lit(scripts_ / "bytecode.lua"))),
      {"binary chunk"});
  expectRefused(run(write_file + fmt::format("dofile({})", lit(scripts_ / "bytecode.lua"))),
                {"binary chunk"});
  expectRefused(run(write_file + "require('bytecode')"),
                {"error loading module 'bytecode'", "binary chunk"});
  expectOk(run(dump + "assert(load(code)() == 7)", unsafe()));
}

// --- Reading outside ---------------------------------------------------------------------------

TEST_F(LuaSandbox, ReadingEtcPasswdIsRefused) {
  const struct {
    const char* function;
    const char* attack;
  } attacks[] = {
      {"io.open", "assert(io.open('/etc/passwd')):read('a')"},
      {"io.open", "assert(io.open('/etc/passwd', 'rb')):read('a')"},
      {"io.lines", "for line in io.lines('/etc/passwd') do end"},
      {"dofile", "dofile('/etc/passwd')"},
      {"loadfile", "loadfile('/etc/passwd')"},
      {"io.input", "io.input('/etc/passwd') io.read('a')"},
  };
  for (const auto& attack : attacks) {
    SCOPED_TRACE(attack.attack);
    // The message names the function, the file, the sandbox and the folders that are allowed.
    expectRefused(run(attack.attack),
                  {std::string(attack.function) + ": /etc/passwd", "sandbox", scripts_.string()});
  }
  if (!fs::exists("/etc/passwd")) GTEST_SKIP() << "no /etc/passwd to read under --unsafe";
  expectOk(run("assert(#assert(io.open('/etc/passwd')):read('a') > 0)", unsafe()));
}

TEST_F(LuaSandbox, CodeFromStandardInputIsRefused) {
  expectRefused(run("dofile()"), {"dofile", "standard input"});
  expectRefused(run("loadfile()"), {"loadfile", "standard input"});
}

TEST_F(LuaSandbox, DotDotEscapeIsRefused) {
  const std::string escape = (scripts_ / ".." / "outside" / "secret.txt").string();
  expectRefused(run(fmt::format("io.open({})", lit(escape))), {"io.open", escape, "sandbox"});
  // Relative paths resolve against the current folder, as Lua's own io.open does.
  CurrentFolder in_scripts(scripts_);
  expectRefused(run("io.open('../outside/secret.txt')"), {"io.open", "../outside/secret.txt"});
  expectOk(run("assert(assert(io.open('own.txt')):read('a') == 'own')"));
}

// --- Writing outside ---------------------------------------------------------------------------

TEST_F(LuaSandbox, WritingOutsideIsRefused) {
  const fs::path created = outside_ / "new.txt";
  const fs::path secret = outside_ / "secret.txt";
  const fs::path own = scripts_ / "own.txt";
  const struct {
    std::string function;
    std::string attack;
    fs::path named;
  } attacks[] = {
      {"io.open", fmt::format("io.open({}, 'w')", lit(created)), created},
      {"io.open", fmt::format("io.open({}, 'a')", lit(created)), created},
      {"io.open", fmt::format("io.open({}, 'r+')", lit(secret)), secret},
      {"io.output", fmt::format("io.output({})", lit(created)), created},
      {"os.remove", fmt::format("os.remove({})", lit(secret)), secret},
      {"os.rename", fmt::format("os.rename({}, {})", lit(own), lit(created)), created},
      {"os.rename", fmt::format("os.rename({}, {})", lit(secret), lit(scripts_ / "stolen.txt")),
       secret},
  };
  for (const auto& attack : attacks) {
    SCOPED_TRACE(attack.attack);
    expectRefused(run(attack.attack),
                  {attack.function + ": " + attack.named.string(), "sandbox", "--allow-write"});
  }
  EXPECT_FALSE(fs::exists(created));
  EXPECT_EQ(readFile(secret), "secret");
  EXPECT_EQ(readFile(own), "own");
  EXPECT_FALSE(fs::exists(scripts_ / "stolen.txt"));
}

// --- Symbolic links inside the script's folder ---------------------------------------------------

TEST_F(LuaSandbox, SymlinkOutOfScriptFolderIsRefused) {
  const struct {
    std::string function;
    std::string attack;
  } attacks[] = {
      {"io.open", fmt::format("io.open({})", lit(scripts_ / "out_file"))},
      {"io.open", fmt::format("io.open({})", lit(scripts_ / "out_dir" / "secret.txt"))},
      {"io.lines", fmt::format("io.lines({})", lit(scripts_ / "out_file"))},
      {"io.open", fmt::format("io.open({}, 'w')", lit(scripts_ / "out_dir" / "new.txt"))},
      // A link to a file not made yet: opening it for writing would create the target outside.
      {"io.open", fmt::format("io.open({}, 'w')", lit(scripts_ / "dangling"))},
      {"os.remove", fmt::format("os.remove({})", lit(scripts_ / "out_dir" / "secret.txt"))},
  };
  for (const auto& attack : attacks) {
    SCOPED_TRACE(attack.attack);
    const ScriptOutcome outcome = run(attack.attack);
    expectRefused(outcome,
                  {attack.function, "sandbox", "a symbolic link on the path leads outside"});
    // Where the link leads is outside the script's folders: the message must not tell it.
    EXPECT_EQ(outcome.message.find(outside_.string()), std::string::npos) << outcome.message;
  }
  EXPECT_FALSE(fs::exists(outside_ / "new.txt"));
  EXPECT_FALSE(fs::exists(outside_ / "created.txt"));
  EXPECT_EQ(readFile(outside_ / "secret.txt"), "secret");

  // The dangling link is a real way out: without the sandbox, writing it creates the target.
  expectOk(run(fmt::format("assert(io.open({}, 'w')):write('x')", lit(scripts_ / "dangling")),
               unsafe()));
  EXPECT_TRUE(fs::exists(outside_ / "created.txt"));
}

// --- What stays allowed ------------------------------------------------------------------------

TEST_F(LuaSandbox, ScriptFolderIsReadableAndWritable) {
  expectOk(run(fmt::format(R"(
    local folder = {}
    local f = assert(io.open(folder .. '/result.txt', 'w'))
    f:write('1 2 3') f:close()
    assert(assert(io.open(folder .. '/result.txt')):read('a') == '1 2 3')
    local n = 0 for line in io.lines(folder .. '/own.txt') do n = n + 1 end
    assert(n == 1)
    assert(os.rename(folder .. '/result.txt', folder .. '/renamed.txt'))
    assert(os.remove(folder .. '/own.txt'))
    assert(dofile(folder .. '/helper.lua').answer == 42)
    assert(loadfile(folder .. '/helper.lua')().answer == 42)
  )",
                           lit(scripts_))));
  EXPECT_EQ(readFile(scripts_ / "renamed.txt"), "1 2 3");
  EXPECT_FALSE(fs::exists(scripts_ / "result.txt"));
  EXPECT_FALSE(fs::exists(scripts_ / "own.txt"));
}

TEST_F(LuaSandbox, RequireFindsLuaModulesBesideTheScript) {
  writeFile(scripts_ / "main.lua", R"(
    local helper = require('helper')
    assert(helper.answer == 42)
    assert(require('pkg.sub') == 'sub')
    assert(require('helper') == helper, 'loaded once')
  )");
  ScriptHost host(scripts_ / "main.lua", sandboxed());
  expectOk(host.run());
}

TEST_F(LuaSandbox, RequireCannotReachOutside) {
  const std::string attack =
      fmt::format("package.path = {} .. '/?.lua' return require('secretmod')", lit(outside_));
  expectRefused(run(attack),
                {"module 'secretmod' not found", (outside_ / "secretmod.lua").string(), "sandbox"});
  // Through `..` in the module name and through a link in the script's folder.
  expectRefused(run("require('../outside/secretmod')"), {"secretmod.lua", "sandbox"});
  expectRefused(run("require('out_dir.secretmod')"), {"out_dir/secretmod.lua", "sandbox"});
  // package.searchpath does not probe outside either.
  expectOk(
      run(fmt::format("local found, tried = package.searchpath('secretmod', {} .. '/?.lua') "
                      "assert(found == nil and tried:find('sandbox'))",
                      lit(outside_))));
  expectOk(run("assert(package.searchpath('helper', package.path))"));
  expectOk(run(attack, unsafe()));
}

// The wrappers report a wrong argument under the function's own name, as Lua does.
TEST_F(LuaSandbox, ArgumentErrorsNameTheFunction) {
  expectRefused(run("io.open('own.txt', 'rw')"), {"bad argument #2 to 'open' (invalid mode)"});
  expectRefused(run("io.open({})"), {"bad argument #1 to 'open' (string expected, got table)"});
  expectRefused(run("os.remove()"),
                {"bad argument #1 to 'remove' (string expected, got no value)"});
  expectRefused(run("os.rename('a')"),
                {"bad argument #2 to 'rename' (string expected, got no value)"});
  expectRefused(run("dofile({})"), {"bad argument #1 to 'dofile' (string expected, got table)"});
}

TEST_F(LuaSandbox, AllowReadFolderIsReadableNotWritable) {
  const fs::path data = allowRead_ / "data.txt";
  const std::string read =
      fmt::format("assert(assert(io.open({})):read('a') == 'data')", lit(data));
  expectRefused(run(read), {"io.open", data.string(), "--allow-read"});
  ScriptOptions options = sandboxed();
  options.sandbox.allowRead = {allowRead_};
  expectOk(run(read, options));
  expectRefused(run(fmt::format("io.open({}, 'w')", lit(data)), options),
                {"io.open", data.string(), "writing is not allowed"});
  expectRefused(run(fmt::format("os.remove({})", lit(data)), options), {"os.remove"});
  EXPECT_EQ(readFile(data), "data");
}

TEST_F(LuaSandbox, AllowWriteFolderIsWritable) {
  const fs::path out = allowWrite_ / "out.txt";
  const std::string write = fmt::format(R"(
    local f = assert(io.open({0}, 'w')) f:write('written') f:close()
    assert(assert(io.open({0})):read('a') == 'written')
  )",
                                        lit(out));
  expectRefused(run(write), {"io.open", out.string(), "--allow-write"});
  ScriptOptions options = sandboxed();
  options.sandbox.allowWrite = {allowWrite_};
  expectOk(run(write, options));
  EXPECT_EQ(readFile(out), "written");
}

TEST_F(LuaSandbox, ModelRootsAreReadable) {
  const fs::path model = models_ / "hand.xml";
  const std::string read =
      fmt::format("assert(assert(io.open({})):read('a') == '<robot/>')", lit(model));
  expectRefused(run(read), {"io.open", model.string()});
  ScriptOptions options = sandboxed();
  options.load.roots = {models_};
  expectOk(run(read, options));
  expectRefused(run(fmt::format("io.open({}, 'a')", lit(model)), options),
                {"io.open", "writing is not allowed"});
}

// A table's __gc would run with hooks off, beyond the time limit's reach.
TEST_F(LuaSandbox, FinalizersAreRefused) {
  expectRefused(run("setmetatable({}, {__gc = function() while true do end end})"),
                {"setmetatable", "__gc", "sandbox"});
  expectOk(run("assert(getmetatable(setmetatable({}, {__index = {x = 1}})).__index.x == 1)"));
}

// --- Paths with NUL bytes, files that model files name, userdata ---------------------------------

// The OS opens a path only up to its first NUL byte; the check would see all of it. Here the
// whole string normalises into the script's folder while its head names a file outside.
TEST_F(LuaSandbox, PathsWithNulBytesAreRefused) {
  writeFile(outside_ / "w.xml", "<world></world>");
  const std::string tail = R"(\0/../../scripts/own.txt')";
  const std::string head = "'" + (outside_ / "w.xml").string();
  expectRefused(run("graspkit.load_world(" + head + tail + ")"), {"load_world", "NUL"});
  expectRefused(run("graspkit.new_world():add_object(" + head + tail + ")"), {"NUL"});
  const std::string made = "'" + (outside_ / "made.xml").string();
  expectRefused(run("graspkit.new_world():save(" + made + tail + ")"), {"save", "NUL"});
  EXPECT_FALSE(fs::exists(outside_ / "made.xml"));
  expectRefused(run("io.open(" + made + tail + ", 'w')"), {"io.open"});
  EXPECT_FALSE(fs::exists(outside_ / "made.xml"));
  // Refused under --unsafe too: such a path names no file anyone meant.
  expectRefused(run("graspkit.load_world(" + head + tail + ")", unsafe()), {"NUL"});
}

// A script may write a model file into its folder; the files that model names (geometry, robot,
// eigengrasps) are read under the same policy, and the refusal quotes nothing from them.
TEST_F(LuaSandbox, FilesNamedByModelFilesObeyThePolicy) {
  writeFile(outside_ / "secret.iv", "TOP-SECRET-CONTENT line two\n");
  const std::string body = "<root><material>plastic</material><geometryFile type=\"Inventor\">" +
                           (outside_ / "secret.iv").string() + "</geometryFile></root>";
  const std::string write =
      fmt::format("local f = assert(io.open({}, 'w')) f:write({}) f:close()\n",
                  lit(scripts_ / "evil.xml"), "[==[" + body + "]==]");
  const ScriptOutcome outcome =
      run(write + "graspkit.new_world():add_object('" + (scripts_ / "evil.xml").string() + "')");
  expectRefused(outcome, {"reading is not allowed", (outside_ / "secret.iv").string()});
  EXPECT_EQ(outcome.message.find("TOP-SECRET"), std::string::npos) << outcome.message;
  // A world file naming a body outside, relative to the world's folder.
  writeFile(outside_ / "hidden.xml", body);
  writeFile(scripts_ / "world.xml",
            "<world><graspableBody><filename>../outside/hidden.xml</filename></graspableBody>"
            "</world>");
  expectRefused(run("graspkit.load_world('" + (scripts_ / "world.xml").string() + "')"),
                {"reading is not allowed", "hidden.xml"});
  // Under --unsafe the same files are read: the refusal above is the policy, not a missing file.
  const ScriptOutcome open =
      run(write + "graspkit.new_world():add_object('" + (scripts_ / "evil.xml").string() + "')",
          unsafe());
  EXPECT_EQ(open.message.find("reading is not allowed"), std::string::npos) << open.message;
  EXPECT_NE(open.message.find("not an Inventor or VRML file"), std::string::npos) << open.message;
}

// Userdata metatables are locked: a script cannot reach __gc to destroy a live object, nor the
// methods table to change it; the shared Pose metatable cannot be given a finalizer.
TEST_F(LuaSandbox, MetatablesAreLocked) {
  expectOk(run(R"(
    local w = graspkit.new_world()
    assert(getmetatable(w) == 'graspkit.World', tostring(getmetatable(w)))
    assert(w.__gc == nil and w.__index == nil)
    assert(not pcall(setmetatable, w, {}))
    local p = graspkit.pose({1, 2, 3}, {1, 0, 0, 0})
    assert(getmetatable(p) == 'graspkit.Pose', tostring(getmetatable(p)))
    assert(not pcall(setmetatable, p, {__gc = function() end}))
    assert(#w:bodies() == 0)  -- the world still works
  )"));
}

// --- Resource limits ----------------------------------------------------------------------------

// A script that grows without end meets the memory limit (Lua's own out-of-memory error), and the
// message says which limit and how to raise it. The same script under the limit runs.
TEST_F(LuaSandbox, MemoryLimitStopsARunawayScript) {
  ScriptOptions options = sandboxed();
  options.memoryLimitBytes = std::size_t{32} << 20;
  const std::string grow = "local t = {} for i = 1, 1e9 do t[i] = string.rep('x', 1000) .. i end";
  expectRefused(run(grow, options), {"not enough memory", "memory limit is 32 MiB"});
  expectOk(run("local t = {} for i = 1, 1000 do t[i] = string.rep('x', 1000) .. i end", options));
  EXPECT_EQ(ScriptOptions{}.memoryLimitBytes, ScriptOptions::kDefaultMemoryLimitBytes);
}

// An exit status is one byte: os.exit(256) would exit 0, a failure read as success.
TEST_F(LuaSandbox, ExitStatusOutsideAByteIsRefused) {
  expectRefused(run("os.exit(256)"), {"exit status must be 0..255"});
  expectRefused(run("os.exit(-1)"), {"exit status must be 0..255"});
  const ScriptOutcome three = run("os.exit(3)");
  EXPECT_EQ(three.exitStatus, 3);
}

// --- The time limit ----------------------------------------------------------------------------

class LuaTimeLimit : public LuaSandbox {
 protected:
  static constexpr double kLimit = 0.5;

  static ScriptOptions limited() {
    ScriptOptions options = sandboxed();
    options.timeoutSeconds = kLimit;
    return options;
  }

  // Runs `source` on `host`, expecting the limit to stop it within a second of the limit.
  static void expectStopped(ScriptHost& host, const std::string& source) {
    const auto start = std::chrono::steady_clock::now();
    const ScriptOutcome outcome = host.runString(source, "loop");
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_FALSE(outcome.ok);
    EXPECT_TRUE(outcome.timedOut) << outcome.message;
    EXPECT_NE(outcome.message.find("time limit of 0.5 s exceeded (--timeout 0.5)"),
              std::string::npos)
        << outcome.message;
    EXPECT_GE(elapsed, kLimit);
    EXPECT_LT(elapsed, kLimit + 1.0);
  }

  void expectStopped(const std::string& source) {
    ScriptHost host(scripts_ / "main.lua", limited());
    expectStopped(host, source);
  }
};

TEST_F(LuaTimeLimit, InfiniteLoopIsStopped) {
  expectStopped("while true do end");
}

TEST_F(LuaTimeLimit, PcallCannotSwallowTheLimit) {
  expectStopped("while true do pcall(function() while true do end end) end");
  expectStopped("while true do pcall(error, 'x') end");
}

TEST_F(LuaTimeLimit, XpcallHandlerCannotSwallowTheLimit) {
  expectStopped(R"(
    while true do
      xpcall(function() while true do end end, function(m) while true do end end)
    end
  )");
}

// The hook's error leaves Lua's hooks off until a pcall catches it, and Lua calls the message
// handler before that: a looping handler would never be stopped but for the xpcall wrapper.
TEST_F(LuaTimeLimit, XpcallHandlerAfterTheLimitIsNotRun) {
  expectStopped("xpcall(function() while true do end end, function(m) while true do end end)");
  expectStopped("xpcall(error, function(m) while true do end end, 'a normal error')");
}

// The same for a coroutine's __close handlers: its thread keeps hooks off once the limit stopped
// it (no pcall inside it caught the error), and closing it would run them unbounded.
TEST_F(LuaTimeLimit, CloseHandlersOfAStoppedCoroutineAreNotRun) {
  const std::string body = R"(
    function()
      local x <close> = setmetatable({}, {__close = function() while true do end end})
      while true do end
    end
  )";
  expectStopped("local co = coroutine.create(" + body +
                ") coroutine.resume(co) coroutine.close(co)");
  expectStopped("coroutine.wrap(" + body + ")()");
  // Stopped in one call, closed in the next, when no limit is running yet.
  ScriptHost host(scripts_ / "main.lua", limited());
  expectStopped(host, "co = coroutine.create(" + body + ") coroutine.resume(co)");
  const ScriptOutcome later = host.runString(
      "local ok, message = coroutine.close(co) assert(not ok) return message", "later");
  expectOk(later);
}

// In the main thread a pcall catches the hook's error and switches hooks back on: __close
// handlers of the main chunk run under the limit (and stop at once).
TEST_F(LuaTimeLimit, CloseHandlersOfTheMainChunkAreBounded) {
  expectStopped(R"(
    local x <close> = setmetatable({}, {__close = function() while true do end end})
    while true do end
  )");
}

// The wrappers behave as Lua's own functions while the limit is not reached.
TEST_F(LuaTimeLimit, WrappedFunctionsKeepTheirMeaning) {
  ScriptHost host(scripts_ / "main.lua", limited());
  expectOk(host.runString(R"(
    local ok, message = xpcall(error, function(m) return 'handled: ' .. m end, 'x', 0)
    assert(not ok and message == 'handled: x', message)
    assert(select('#', xpcall(function(...) return ... end, print, 1, 2, 3)) == 4)
    -- yields across xpcall and through coroutine.wrap
    local f = coroutine.wrap(function()
      xpcall(function() coroutine.yield(1) end, print)
      return 2
    end)
    assert(f() == 1 and f() == 2)
    local ok2, dead = pcall(f)
    assert(not ok2 and dead:find('cannot resume dead coroutine'), dead)
    -- an error in a wrapped coroutine comes out located, after its __close handlers ran
    local closed = false
    local g = coroutine.wrap(function()
      local x <close> = setmetatable({}, {__close = function() closed = true end})
      error('boom')
    end)
    local ok3, boom = pcall(g)
    assert(not ok3 and boom:find('boom') and closed, boom)
    -- coroutine.close of a coroutine that was not stopped
    local co = coroutine.create(function()
      local x <close> = setmetatable({}, {__close = function() closed = 'again' end})
      coroutine.yield()
    end)
    coroutine.resume(co)
    assert(coroutine.close(co) and closed == 'again')
  )",
                          "wrappers"));
}

// A library call that never returns to the VM (a pattern with exponential backtracking) is beyond
// any hook: the watchdog ends the process a second after the limit, with status 124.
TEST_F(LuaTimeLimit, WatchdogEndsAStuckLibraryCall) {
  const std::string stuck = "string.rep('a', 40):find(string.rep('a*', 40) .. 'b')";
  EXPECT_EXIT(
      {
        ScriptOptions options = limited();
        options.exitProcessWhenStuck = true;
        ScriptHost host(scripts_ / "main.lua", options);
        host.runString(stuck, "stuck");
      },
      ::testing::ExitedWithCode(124),
      "time limit of 0\\.5 s exceeded \\(--timeout 0\\.5\\).*ending the process");
}

// coroutine.resume catches the error raised inside the coroutine; the call still times out.
TEST_F(LuaTimeLimit, LoopInCoroutineIsStopped) {
  expectStopped("coroutine.resume(coroutine.create(function() while true do end end))");
  expectStopped("coroutine.wrap(function() while true do end end)()");
}

// Coroutines made in an earlier call, before this call's limit began.
TEST_F(LuaTimeLimit, CoroutineCreatedBeforeTheLimitIsStopped) {
  ScriptHost host(scripts_ / "main.lua", limited());
  expectOk(host.runString(R"(
    co = coroutine.create(function() while true do end end)
    wrapped = coroutine.wrap(function() while true do pcall(function() while true do end end) end end)
  )",
                          "setup"));
  expectStopped(host, "coroutine.resume(co)");
  expectStopped(host, "wrapped()");
}

// A thread a host binding makes between calls, when no limit is running (lua_newthread copies the
// hook of its creator, so the hook must be there all the time, not only during calls).
TEST_F(LuaTimeLimit, ThreadCreatedOutsideACallIsStopped) {
  ScriptHost host(scripts_ / "main.lua", limited());
  lua_State* L = host.state();
  lua_State* thread = lua_newthread(L);
  ASSERT_EQ(luaL_loadstring(thread, "while true do end"), LUA_OK);
  lua_setglobal(L, "thread");
  expectStopped(host, "coroutine.resume(thread)");
}

TEST_F(LuaTimeLimit, ScriptUnderTheLimitIsUnaffected) {
  ScriptHost host(scripts_ / "main.lua", limited());
  const std::string work = R"(
    local sum = 0
    for i = 1, 100000 do sum = sum + i end
    assert(sum == 100000 * 100001 // 2)
    local co = coroutine.wrap(function() for i = 1, 3 do coroutine.yield(i) end end)
    assert(co() + co() + co() == 6)
  )";
  expectOk(host.runString(work, "work"));
  // After a call that timed out, the next call has its own full limit.
  expectStopped(host, "while true do end");
  expectOk(host.runString(work, "work again"));
  // A call lasting a good part of the limit is not cut short (CPU time, so a busy machine only
  // makes it longer in wall time: hence the wide margin).
  ScriptOptions options = limited();
  options.timeoutSeconds = 3.0;
  ScriptHost roomy(scripts_ / "main.lua", options);
  expectOk(
      roomy.runString("local start = os.clock() while os.clock() - start < 0.5 do end", "busy"));
}

}  // namespace
}  // namespace graspkit::lua
