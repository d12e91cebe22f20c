// The plugin loader against the plugin corpus (tests/plugins): the well-formed plugin loads on
// demand and is recorded with its provenance; each broken plugin is refused with an error that
// names the file and the failure, and registers nothing.

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/plugin/registry.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = GRASPKIT_PLUGIN_CORPUS_DIR;
const fs::path kGood = kCorpus / "good";
const fs::path kBroken = kCorpus / "broken";
const fs::path kThrowing = kCorpus / "throwing";
const fs::path kDeadly = kCorpus / "deadly";
const fs::path kUnruly = kCorpus / "unruly";

// The error message of loading `file` into a fresh registry whose path holds only the good plugin.
std::string loadError(const std::string& file) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood});
  registry.plugins().load(kGood / "good.so");
  try {
    registry.plugins().load(kBroken / file);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " loaded without an error";
  return "";
}

// A copy of the project's parallel-jaw gripper whose <robot type> is `type`.
fs::path gripperOfType(const std::string& type) {
  const fs::path dir = test::scratchDir() / "gripper";
  fs::copy(test::modelsDir() / "robots" / "parallel_jaw", dir, fs::copy_options::recursive);
  const fs::path file = dir / "parallel_jaw.xml";
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string xml = text.str();
  const std::string from = "type=\"Hand\"";
  xml.replace(xml.find(from), from.size(), "type=\"" + type + "\"");
  std::ofstream(file) << xml;
  return file;
}

TEST(PluginLoader, LoadsThePluginProvidingARequestedTypeOnDemand) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood});
  EXPECT_FALSE(registry.contains(FactoryKind::RobotType, "CorpusGripper"));
  ASSERT_NE(registry.robotType("CorpusGripper"), nullptr);
  const auto from = registry.provenance(FactoryKind::RobotType, "CorpusGripper");
  ASSERT_TRUE(from);
  EXPECT_EQ(from->plugin, "corpus_good");
  EXPECT_EQ(from->version, "2.3.4");
  EXPECT_EQ(fs::canonical(from->file), fs::canonical(kGood / "good.so"));
  // The same plugin brought its quality measure along.
  EXPECT_EQ(registry.makeQualityMeasure("corpus_constant")->evaluate(GraspWrenchSpace{}), 42.0);
}

// Whatever a plugin's factory or robot type throws, a std::exception or not, reaches the host as
// a graspkit::Error naming the plugin: never std::terminate, never an anonymous "internal error".
TEST(PluginLoader, ThrowingFactoriesBecomeErrorsNamingThePlugin) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kThrowing});
  const auto errorOf = [](auto&& make) -> std::string {
    try {
      make();
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  };
  const std::string standard = errorOf([&] { registry.makeQualityMeasure("corpus_throws_std"); });
  EXPECT_NE(standard.find("corpus_throwing 0.1"), std::string::npos) << standard;
  EXPECT_NE(standard.find("calibration table missing"), std::string::npos) << standard;
  const std::string other = errorOf([&] { registry.makeQualityMeasure("corpus_throws_int"); });
  EXPECT_NE(other.find("corpus_throwing 0.1"), std::string::npos) << other;
  EXPECT_NE(other.find("not a std::exception"), std::string::npos) << other;
  LoadOptions options;
  options.registry = &registry;
  const fs::path robot = gripperOfType("CorpusConfigureThrows");
  const std::string configure = errorOf([&] { loadRobotFile(robot, options); });
  EXPECT_NE(configure.find(robot.string()), std::string::npos) << configure;
  EXPECT_NE(configure.find("CorpusConfigureThrows"), std::string::npos) << configure;
  EXPECT_NE(configure.find("not a std::exception"), std::string::npos) << configure;
}

TEST(PluginLoader, TheRobotTypeConfiguresTheModel) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood});
  LoadOptions options;
  options.registry = &registry;
  const auto model = loadRobotFile(gripperOfType("CorpusGripper"), options);
  EXPECT_EQ(model->typeProvider, "corpus_good 2.3.4");
  ASSERT_EQ(model->disabledCollisions.size(), 1u);
  EXPECT_TRUE(model->disabledCollisions[0].first.isBase());
  EXPECT_EQ(model->disabledCollisions[0].second, (LinkRef{0, 0}));
}

TEST(PluginLoader, LoadingTheSameFileTwiceIsOneLoad) {
  Registry registry;
  const PluginInfo& first = registry.plugins().load(kGood / "good.so");
  const PluginInfo& second = registry.plugins().load(kGood / "." / "good.so");
  EXPECT_EQ(&first, &second);
  EXPECT_EQ(registry.plugins().loaded().size(), 1u);
}

struct BrokenCase {
  const char* file;
  const char* says;
  const char* neverRegistered;  // a name the plugin tried to register, or ""
};

class BrokenPlugin : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenPlugin, IsRefusedWithAnErrorNamingTheFileAndRegistersNothing) {
  const BrokenCase& c = GetParam();
  const std::string message = loadError(c.file);
  EXPECT_NE(message.find((kBroken / c.file).string()), std::string::npos) << message;
  EXPECT_NE(message.find(c.says), std::string::npos) << message;
  EXPECT_NE(message.find("plugin search path: " + kGood.string()), std::string::npos) << message;

  Registry registry;
  registry.plugins().load(kGood / "good.so");
  EXPECT_THROW(registry.plugins().load(kBroken / c.file), Error);
  if (*c.neverRegistered)
    EXPECT_FALSE(registry.contains(FactoryKind::RobotType, c.neverRegistered));
  EXPECT_EQ(registry.names(FactoryKind::RobotType),
            (std::vector<std::string>{"CorpusGripper", "Hand", "Robot"}));
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, BrokenPlugin,
    ::testing::Values(
        BrokenCase{"wrong_abi.so", "built for plugin ABI 999, this engine loads ABI 3",
                   "WrongAbiType"},
        BrokenCase{"wrong_size.so", "descriptor size", "WrongSizeType"},
        BrokenCase{"no_symbol.so", "not a graspkit plugin: no symbol graspkit_plugin_v1", ""},
        BrokenCase{"null_descriptor.so", "returned no descriptor", ""},
        BrokenCase{"throws.so", "threw while registering: calibration table missing",
                   "HalfRegisteredType"},
        BrokenCase{"duplicate_type.so",
                   "provides robot type 'CorpusGripper', already provided by corpus_good 2.3.4",
                   "DuplicateOnlyType"},
        BrokenCase{"twice_in_one.so", "registers robot type 'TwiceType' twice", "TwiceType"},
        BrokenCase{"same_name.so", "a plugin named 'corpus_good' is already loaded",
                   "ImpostorType"},
        BrokenCase{"empty_names.so", "registers a robot type with no name", ""},
        BrokenCase{"not_utf8_names.so", "registers a robot type whose name is not UTF-8 text", ""},
        BrokenCase{"not_elf.so", "cannot load", ""}),
    [](const auto& info) { return fs::path(info.param.file).stem().string(); });

TEST(PluginLoader, AMissingFileIsAnError) {
  Registry registry;
  try {
    registry.plugins().load(kCorpus / "no_such_plugin.so");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_plugin.so: no such file"), std::string::npos)
        << e.what();
  }
}

TEST(PluginLoader, UnknownRobotTypeNamesTheFileTheTypesAndThePath) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood, kBroken});
  LoadOptions options;
  options.registry = &registry;
  const fs::path file = gripperOfType("NoSuchType");
  try {
    loadRobotFile(file, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string() + ":"), std::string::npos) << message;
    EXPECT_NE(message.find("<robot>"), std::string::npos) << message;
    EXPECT_NE(message.find("unknown robot type 'NoSuchType'"), std::string::npos) << message;
    EXPECT_NE(message.find("available: CorpusGripper, Hand, Robot"), std::string::npos) << message;
    EXPECT_NE(message.find(kGood.string() + ":" + kBroken.string()), std::string::npos) << message;
    EXPECT_NE(message.find("throws.so failed to load"), std::string::npos) << message;
  }
}

TEST(PluginLoader, GenericFallbackOnlyWhenAskedAndSaysSo) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood});
  LoadOptions options;
  options.registry = &registry;
  options.genericRobotFallback = true;
  std::vector<std::string> warnings;
  const WarningHandler previous = setWarningHandler([&](const Warning& w) {
    EXPECT_EQ(w.kind, WarningKind::Plugin);
    warnings.push_back(w.message);
  });
  const auto model = loadRobotFile(gripperOfType("NoSuchType"), options);
  setWarningHandler(previous);
  EXPECT_EQ(model->type, "NoSuchType");
  EXPECT_EQ(model->typeProvider, "generic fallback");
  EXPECT_TRUE(model->isHand);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("loaded as a generic Hand"), std::string::npos) << warnings[0];
}

TEST(PluginLoader, LoadAllReportsEveryFileLoadedOrNot) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood, kBroken});
  const std::vector<PluginInfo> all = registry.plugins().loadAll();
  ASSERT_EQ(all.size(), 12u);  // good + eleven broken files
  int loaded = 0;
  for (const PluginInfo& info : all) {
    if (info.loaded) {
      ++loaded;
      EXPECT_EQ(info.name, "corpus_good");
      EXPECT_EQ(describeProvides(info),
                "robot type CorpusGripper, quality measure corpus_constant");
    } else {
      EXPECT_FALSE(info.error.empty()) << info.file;
    }
  }
  EXPECT_EQ(loaded, 1);
  EXPECT_EQ(registry.plugins().failures().size(), 11u);
}

TEST(PluginLoader, SearchesTheEnvironmentFirstThenBesideTheEngine) {
  const char* old = std::getenv("GRASPKIT_PLUGIN_PATH");
  const std::string saved = old ? old : "";
  setenv("GRASPKIT_PLUGIN_PATH", (kGood.string() + ":/nonexistent/folder").c_str(), 1);
  Registry registry;
  const std::vector<fs::path> path = registry.plugins().searchPath();
  if (old)
    setenv("GRASPKIT_PLUGIN_PATH", saved.c_str(), 1);
  else
    unsetenv("GRASPKIT_PLUGIN_PATH");
  // The environment's folders, then the one beside libgraspkit, and nothing else: no folder
  // fixed at configure time, which a `cmake --install --prefix` elsewhere would leave behind.
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[0], kGood);
  EXPECT_EQ(path[1], fs::path("/nonexistent/folder"));
  const fs::path beside = fs::path(GRASPKIT_BINARY_DIR) / "lib" / "graspkit" / "plugins";
  EXPECT_EQ(fs::weakly_canonical(path[2]), fs::weakly_canonical(beside));
}

TEST(PluginLoader, TheEngineFindsItsOwnPluginsWithoutConfiguration) {
  Registry registry;
  registry.plugins().setSearchPath(std::nullopt);
  ASSERT_NE(registry.robotType("Robonaut"), nullptr);
  const auto from = registry.provenance(FactoryKind::RobotType, "Robonaut");
  ASSERT_TRUE(from);
  EXPECT_EQ(from->plugin, "robonaut");
  EXPECT_EQ(fs::canonical(from->file.parent_path()),
            fs::canonical(fs::path(GRASPKIT_BINARY_DIR) / "lib" / "graspkit" / "plugins"));
}

// ---------------------------------------------------------------------------------------------
// The probe: plugins are opened in a child process before they enter this one

std::string failureOf(Registry& registry, const std::string& file) {
  for (const PluginInfo& info : registry.plugins().failures())
    if (info.file.filename() == file) return info.error;
  return "(not among the failures)";
}

// Plugins that abort (in a static constructor or their register function), call exit() or never
// return, placed before the good plugin on the path, cost a world that needs the good one nothing
// but warnings: this process survives to check, and each failure says what happened.
TEST(PluginProbe, PluginsThatCrashExitOrHangAreContained) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kDeadly, kGood});
  registry.plugins().setProbe(PluginProbe{true, std::chrono::milliseconds(1500)});
  std::vector<std::string> warnings;
  const WarningHandler previous = setWarningHandler([&](const Warning& warning) {
    EXPECT_EQ(warning.kind, WarningKind::Plugin);
    warnings.push_back(warning.message);
  });
  EXPECT_TRUE(registry.plugins().loadProviding(FactoryKind::RobotType, "CorpusGripper"));
  setWarningHandler(previous);
  EXPECT_EQ(registry.plugins().failures().size(), 4u);
  // Under AddressSanitizer a crash may end the child through the sanitizer's exit instead.
  for (const char* file : {"aborts.so", "aborts_on_open.so"}) {
    const std::string error = failureOf(registry, file);
    EXPECT_TRUE(error.find("crashed while loading: signal 6") != std::string::npos ||
                error.find("ended the process while loading") != std::string::npos)
        << file << ": " << error;
  }
  EXPECT_NE(failureOf(registry, "exits.so").find("ended the process while loading (exit status"),
            std::string::npos)
      << failureOf(registry, "exits.so");
  EXPECT_NE(failureOf(registry, "hangs.so").find("did not finish loading within 1.5 s"),
            std::string::npos)
      << failureOf(registry, "hangs.so");
  EXPECT_EQ(warnings.size(), 4u);
  ASSERT_EQ(registry.plugins().loaded().size(), 1u);
  EXPECT_EQ(registry.plugins().loaded()[0].name, "corpus_good");
}

// Loading a deadly plugin by name is an error naming it, not the end of the host.
TEST(PluginProbe, LoadingACrashingPluginByNameIsAnError) {
  Registry registry;
  try {
    registry.plugins().load(kDeadly / "aborts_on_open.so");
    FAIL() << "a plugin that aborts while loading loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((kDeadly / "aborts_on_open.so").string()),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("while loading"), std::string::npos) << e.what();
  }
}

// Of the healthy plugins, only the one that provides a needed name enters the process; the
// probe's errors are the ones an in-process load gives.
TEST(PluginProbe, OnlyThePluginProvidingTheNameIsLoaded) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kThrowing, kBroken, kGood});
  EXPECT_TRUE(registry.plugins().loadProviding(FactoryKind::QualityMeasure, "corpus_constant"));
  std::vector<std::string> loaded;
  for (const PluginInfo& info : registry.plugins().loaded()) loaded.push_back(info.name);
  EXPECT_EQ(loaded, std::vector<std::string>{"corpus_good"});
  EXPECT_EQ(failureOf(registry, "wrong_abi.so"),
            "built for plugin ABI 999, this engine loads ABI 3");
  EXPECT_FALSE(registry.contains(FactoryKind::QualityMeasure, "corpus_throws_std"));
  EXPECT_TRUE(registry.plugins().loadProviding(FactoryKind::QualityMeasure, "corpus_throws_std"));
  EXPECT_EQ(registry.plugins().loaded().size(), 2u);
}

// Listing plugins loads none into the process: a plugin that behaves in the probe and crashes
// when loaded again (it leaves a marker the first time) is listed, and the host lives on. The
// listing finds the clashes a load would: the broken folder's duplicate_type provides the good
// plugin's robot type.
TEST(PluginProbe, SurveyListsWithoutLoading) {
  const fs::path marker = test::scratchDir() / "second_load_marker";
  fs::remove(marker);
  setenv("GRASPKIT_TEST_MARKER", marker.c_str(), 1);
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kGood, kUnruly, kBroken});
  const std::vector<PluginInfo> listed = registry.plugins().survey();
  unsetenv("GRASPKIT_TEST_MARKER");
  EXPECT_TRUE(fs::exists(marker)) << "the probe's child did not load the plugin";
  EXPECT_TRUE(registry.plugins().loaded().empty());
  std::map<std::string, const PluginInfo*> by_file;
  for (const PluginInfo& info : listed) by_file[info.file.filename().string()] = &info;
  ASSERT_TRUE(by_file.count("second_load_crashes.so"));
  EXPECT_TRUE(by_file["second_load_crashes.so"]->loaded)
      << by_file["second_load_crashes.so"]->error;
  ASSERT_TRUE(by_file.count("good.so") && by_file.count("duplicate_type.so"));
  EXPECT_TRUE(by_file["good.so"]->loaded);
  EXPECT_FALSE(by_file["duplicate_type.so"]->loaded);
  EXPECT_NE(by_file["duplicate_type.so"]->error.find("already provided by plugin 'corpus_good'"),
            std::string::npos)
      << by_file["duplicate_type.so"]->error;
  EXPECT_FALSE(by_file["wrong_abi.so"]->loaded);
}

// What a plugin prints while it loads never reaches standard output (the probe's child throws it
// away; an in-process load sends it to standard error), so --json output stays JSON.
TEST(PluginProbe, PluginOutputStaysOffStandardOutput) {
  Registry registry;
  registry.plugins().setSearchPath(std::vector<fs::path>{kUnruly});
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const bool loaded = registry.plugins().loadProviding(FactoryKind::QualityMeasure, "corpus_noisy");
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(loaded);
  EXPECT_EQ(out, "");
  EXPECT_NE(err.find("NOISE from the register function"), std::string::npos) << err;
}

// With the probe off (GRASPKIT_PLUGIN_PROBE=0), plugins load in place, in path order.
TEST(PluginProbe, TheProbeCanBeTurnedOff) {
  setenv("GRASPKIT_PLUGIN_PROBE", "0", 1);
  Registry registry;
  EXPECT_FALSE(registry.plugins().probe().inChildProcess);
  unsetenv("GRASPKIT_PLUGIN_PROBE");
  EXPECT_TRUE(registry.plugins().probe().inChildProcess);
  registry.plugins().setProbe(PluginProbe{false, std::chrono::milliseconds(1000)});
  registry.plugins().setSearchPath(std::vector<fs::path>{kThrowing, kGood});
  EXPECT_TRUE(registry.plugins().loadProviding(FactoryKind::RobotType, "CorpusGripper"));
  EXPECT_EQ(registry.plugins().loaded().size(), 2u);  // the throwing plugin too, met on the way
}

}  // namespace
}  // namespace graspkit
