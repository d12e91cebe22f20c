// The bad-input corpus (tests/badinput/corpus): every file must fail to load with a
// graspkit::Error (never a crash, never another exception type) whose message names the file,
// the line and the element where the input is wrong, and says why.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/eigengrasp_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

fs::path corpus() {
  return test::sourceDir() / "tests" / "badinput" / "corpus";
}

struct BadInput {
  const char* name;     // test name
  const char* path;     // the file loaded, relative to the corpus
  const char* culprit;  // the file name the message must blame (may be a file `path` names)
  int line;             // where the bad element is in `culprit`
  const char* element;  // the bad element's name
  const char* reason;   // a key phrase of the reason
};

void PrintTo(const BadInput& input, std::ostream* os) {
  *os << input.path;
}

const BadInput kCorpus[] = {
    {"MalformedXml", "robots/malformed_unclosed.xml", "malformed_unclosed.xml", 5, "dof",
     "malformed XML"},
    {"MissingGeometryFile", "bodies/missing_geometry.xml", "missing_geometry.xml", 5,
     "geometryFile", "cannot load geometry"},
    {"UnknownMaterial", "bodies/unknown_material.xml", "unknown_material.xml", 5, "material",
     "unknown material 'unobtainium'"},
    {"DofIndexOutOfRange", "robots/dof_index_out_of_range.xml", "dof_index_out_of_range.xml", 13,
     "theta", "expression 'd9+5' names dof 9, robot has 4"},
    {"NanInTranslation", "robots/nan_translation.xml", "nan_translation.xml", 9, "translation",
     "'nan' is not a finite number"},
    {"LinkCountMismatch", "robots/link_count_mismatch.xml", "link_count_mismatch.xml", 6, "chain",
     "has 3 joints but its 2 links use 2"},
    {"MissingRobotFile", "worlds/missing_robot.xml", "missing_robot.xml", 4, "filename",
     "'robots/no_such_robot.xml' not found"},
    {"WrongDofValueCount", "worlds/wrong_dof_count.xml", "wrong_dof_count.xml", 5, "dofValues",
     "3 values given, robot 'good_hand' (2 DOFs) takes 2"},
    {"NoPalm", "robots/no_palm.xml", "no_palm.xml", 3, "robot", "missing <palm>"},
    {"UnknownJointType", "robots/unknown_joint_type.xml", "unknown_joint_type.xml", 8, "joint",
     "joint type 'Spherical' is not Revolute or Prismatic"},
    {"NegativeSpringStiffness", "robots/negative_spring.xml", "negative_spring.xml", 14,
     "springStiffness", "must not be negative"},
    {"YoungsNotPositive", "bodies/youngs_not_positive.xml", "youngs_not_positive.xml", 5, "youngs",
     "must be greater than 0"},
    {"NormalComplianceWithoutShear", "bodies/normal_without_shear.xml", "normal_without_shear.xml",
     6, "normalCompliance", "give both or neither"},
    {"BadRotationAxis", "robots/bad_rotation_axis.xml", "bad_rotation_axis.xml", 9, "rotation",
     "found '90 w'"},
    {"FullTransformThreeQuaternionNumbers", "worlds/full_transform_three_numbers.xml",
     "full_transform_three_numbers.xml", 6, "fullTransform", "expected '(w x y z)[x y z]'"},
    {"SecondRootElement", "worlds/two_roots.xml", "two_roots.xml", 5, "world",
     "content after the root element <world>"},
    {"ScaleOverflow", "bodies/scale_overflow.xml", "scale_overflow.xml", 5, "geometryScaling",
     "beyond the 1e+09 mm a model coordinate may hold"},
    {"FlockSensorNumberOverflow", "bodies/flock_number_overflow.xml", "flock_number_overflow.xml",
     5, "useFlockOfBirds", "takes a sensor number"},
    {"ConnectionToMissingChain", "worlds/bad_connection_chain.xml", "bad_connection_chain.xml", 9,
     "connection", "has 1 chains, connection names chain 3"},
};

// Files in the corpus that are not bad inputs themselves: valid parts the bad files use.
const std::set<std::string> kSupportFiles = {"robots/good_hand.xml",
                                             "robots/iv/cube.xml",
                                             "robots/iv/cube.off",
                                             "robots/eigen_wrong_dims.xml",
                                             "robots/eigen_index_overflow.xml",
                                             "robots/eigengrasp_wrong_dims.xml",
                                             "robots/eigengrasp_index_overflow.xml",
                                             "bodies/good_cube.xml",
                                             "bodies/cube.off"};

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, FailsWithLocatedError) {
  const BadInput& input = GetParam();
  const fs::path file = corpus() / input.path;
  ASSERT_TRUE(fs::is_regular_file(file)) << file;
  LoadOptions options;
  options.useEnvironment = false;
  try {
    loadAnyFile(file, options);
    FAIL() << input.path << " loaded without an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    SCOPED_TRACE(message);
    // "<file>:<line>: <element>" is how SourceLocation reads: file, line and element together.
    const std::string where =
        std::string(input.culprit) + ":" + std::to_string(input.line) + ": <" + input.element + ">";
    EXPECT_NE(message.find(where), std::string::npos) << "expected location: " << where;
    EXPECT_NE(message.find(input.reason), std::string::npos) << "expected reason: " << input.reason;
    // A located error names a real place, never the placeholder for an unknown file.
    EXPECT_EQ(message.find("<input>"), std::string::npos);
  } catch (const std::exception& e) {
    FAIL() << "not a graspkit::Error: " << e.what();
  } catch (...) {
    FAIL() << "an exception that is not a std::exception";
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputTest, ::testing::ValuesIn(kCorpus),
                         [](const ::testing::TestParamInfo<BadInput>& info) {
                           return std::string(info.param.name);
                         });

// Files written here: inputs too large to keep in the corpus.
fs::path writeBody(const std::string& name, const std::string& root_attributes,
                   const std::string& before_root = "") {
  const fs::path folder = test::scratchDir();
  fs::copy_file(corpus() / "bodies" / "cube.off", folder / "cube.off");
  std::ofstream(folder / name) << "<?xml version=\"1.0\" ?>\n"
                               << before_root << "<root " << root_attributes << ">\n"
                               << "  <material>plastic</material>\n  <mass>10</mass>\n"
                               << "  <geometryFile type=\"off\">cube.off</geometryFile>\n"
                               << "</root>\n";
  return folder / name;
}

std::string attributes(int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += "a" + std::to_string(i) + "=\"1\" ";
  return text;
}

// tinyxml2's duplicate check makes many attributes on one element quadratic: the bound refuses
// them before it parses, with the element's line.
TEST(BadInputGenerated, ManyAttributesOnOneElementAreRefused) {
  const fs::path file = writeBody("many_attributes.xml", attributes(40000), "<!-- a = b -->\n");
  try {
    loadBodyFile(file);
    FAIL() << "a body with 40,000 attributes on its root loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("many_attributes.xml:3: <root>"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("more than 256 attributes"), std::string::npos)
        << e.what();
  }
}

// The scan counts only attributes: '=' and '>' inside quoted values and comments, and up to
// 256 attributes on an element, all load.
TEST(BadInputGenerated, AttributeBoundCountsOnlyAttributes) {
  const std::string equals(5000, '=');
  const std::string noise = "<!-- " + equals + " > -->\n";
  const std::string quoted = "q1=\"" + equals + ">\" q2='" + equals + "' ";
  auto body = loadBodyFile(writeBody("quoted.xml", quoted + attributes(254), noise));
  EXPECT_EQ(body->mesh->triangleCount(), 12u);
  EXPECT_THROW(loadBodyFile(writeBody("one_too_many.xml", quoted + attributes(255))), Error);
}

// A robot file with `dofs` DOFs, one chain of `joints` joints (theta d0) and `fixed` Fixed links
// after its Revolute ones, one element per line so the culprit's line is known.
fs::path writeRobot(const std::string& name, int dofs, int joints, int fixed) {
  const fs::path folder = test::scratchDir();
  fs::copy(corpus() / "robots" / "iv", folder / "iv");
  std::ofstream out(folder / name);
  out << "<?xml version=\"1.0\" ?>\n<robot type=\"Hand\">\n<palm>cube.xml</palm>\n";
  for (int i = 0; i < dofs; ++i)
    out << "<dof type=\"r\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort><Kp>1</Kp>"
           "<Kd>1</Kd><draggerScale>1</draggerScale></dof>\n";
  out << "<chain>\n";
  for (int i = 0; i < joints; ++i)
    out << "<joint type=\"Revolute\"><theta>d0</theta><d>0</d><a>10</a><alpha>0</alpha>"
           "<minValue>-90</minValue><maxValue>90</maxValue></joint>\n";
  for (int i = 0; i < joints; ++i) out << "<link dynamicJointType=\"Revolute\">cube.xml</link>\n";
  for (int i = 0; i < fixed; ++i) out << "<link dynamicJointType=\"Fixed\">cube.xml</link>\n";
  out << "</chain>\n</robot>\n";
  return folder / name;
}

void expectRobotRefused(const fs::path& file, const std::string& where, const std::string& why) {
  try {
    loadRobotFile(file);
    FAIL() << file << " loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

// A robot's size is bounded where it is read (its default eigengrasps alone hold DOFs^2
// numbers): the first element past each bound is named, and a robot at the bounds loads.
TEST(BadInputGenerated, RobotSizeIsBounded) {
  expectRobotRefused(writeRobot("dofs.xml", kMaxRobotDofs + 1, 1, 0),
                     "dofs.xml:" + std::to_string(4 + kMaxRobotDofs) + ": <dof>",
                     "more than 1024 DOFs in one robot");
  expectRobotRefused(writeRobot("joints.xml", 1, kMaxRobotJoints + 1, 0),
                     "joints.xml:" + std::to_string(6 + kMaxRobotJoints) + ": <joint>",
                     "more than 4096 joints in one robot");
  expectRobotRefused(writeRobot("links.xml", 1, 1, kMaxRobotJoints),
                     "links.xml:" + std::to_string(7 + kMaxRobotJoints) + ": <link>",
                     "more than 4096 links in one robot");
  const auto robot = loadRobotFile(writeRobot("largest.xml", 1, kMaxRobotJoints, 0));
  EXPECT_EQ(robot->jointCount(), kMaxRobotJoints);
}

// ---------------------------------------------------------------------------------------------
// What GraspIt! loads with a warning, graspkit loads with a warning (robot.cpp, dof.cpp,
// eigenGrasp.cpp): each case loads, warns at the right place, and uses what GraspIt! uses.

struct Warnings {
  std::vector<std::string> texts;
  WarningHandler previous;
  Warnings()
      : previous(setWarningHandler([this](const Warning& w) {
          // The kind last: "file:line: message [kind]".
          texts.push_back(describe(w) + " [" + std::string(nameOf(w.kind)) + "]");
        })) {}
  ~Warnings() { setWarningHandler(previous); }
  bool has(const std::string& part) const {
    return std::any_of(texts.begin(), texts.end(),
                       [&](const std::string& t) { return t.find(part) != std::string::npos; });
  }
};

// good_hand.xml with `from` replaced by `to`, written beside a copy of its parts.
fs::path editedHand(const std::string& name, const std::string& from, const std::string& to) {
  const fs::path folder = test::scratchDir();
  fs::copy(corpus() / "robots" / "iv", folder / "iv");
  std::ifstream in(corpus() / "robots" / "good_hand.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::ofstream(folder / name) << text;
  return folder / name;
}

TEST(GraspItLeniency, ReversedJointLimitsAreSwapped) {
  const Warnings warnings;
  const auto hand =
      loadRobotFile(editedHand("reversed.xml", "<minValue>-90</minValue><maxValue>90</maxValue>",
                               "<minValue>60</minValue><maxValue>-30</maxValue>"));
  EXPECT_TRUE(warnings.has("the limits are swapped, as GraspIt! does [robot]"));
  EXPECT_TRUE(warnings.has("reversed.xml:8: <joint>: minValue 60 is greater than maxValue -30"))
      << ::testing::PrintToString(warnings.texts);
  EXPECT_NEAR(hand->dofs[0].min, -30 * M_PI / 180, 1e-12);
  EXPECT_NEAR(hand->dofs[0].max, 60 * M_PI / 180, 1e-12);
}

TEST(GraspItLeniency, EigengraspFileOfOtherDimensionsUsesWhatFits) {
  const Warnings warnings;
  const auto hand = loadRobotFile(corpus() / "robots" / "eigengrasp_wrong_dims.xml");
  EXPECT_TRUE(
      warnings.has("eigen_wrong_dims.xml:2: <EigenGrasps>: dimensions is 3, the robot "
                   "has 2 DOFs"))
      << ::testing::PrintToString(warnings.texts);
  EXPECT_TRUE(warnings.has("eigen_wrong_dims.xml:5: <DimVals>: attribute 'd2' does not name"));
  EXPECT_TRUE(warnings.has("the values for d0..d1 are used [eigengrasp]"));
  EXPECT_FALSE(hand->eigengrasps.identity);
  ASSERT_EQ(hand->eigengrasps.grasps.size(), 1u);
  EXPECT_EQ(hand->eigengrasps.grasps[0].direction, Eigen::Vector2d(1, 0));
}

// d4294967296 is skipped, not wrapped round to d0: the eigengrasp is then all zeros on the
// robot's DOFs, and with none left the robot gets identity eigengrasps.
TEST(GraspItLeniency, EigengraspIndexPastTheDofsIsSkippedNotWrapped) {
  const Warnings warnings;
  const auto hand = loadRobotFile(corpus() / "robots" / "eigengrasp_index_overflow.xml");
  EXPECT_TRUE(
      warnings.has("eigen_index_overflow.xml:6: <DimVals>: attribute 'd4294967296' does "
                   "not name one of the robot's 2 DOFs"))
      << ::testing::PrintToString(warnings.texts);
  EXPECT_TRUE(warnings.has("no eigengrasp fits the robot"));
  EXPECT_TRUE(hand->eigengrasps.identity);
}

TEST(GraspItLeniency, MissingEigengraspAndVirtualContactFilesWarn) {
  const Warnings warnings;
  const auto hand =
      loadRobotFile(editedHand("side_files.xml", "</robot>",
                               "<eigenGrasps>eigen/none.xml</eigenGrasps>\n"
                               "<virtualContacts>virtual/none.xml</virtualContacts>\n</robot>"));
  EXPECT_TRUE(warnings.has("side_files.xml:13: <eigenGrasps>"))
      << ::testing::PrintToString(warnings.texts);
  EXPECT_TRUE(warnings.has("identity eigengrasps are used"));
  EXPECT_TRUE(warnings.has("side_files.xml:14: <virtualContacts>"));
  EXPECT_TRUE(warnings.has("the robot has no virtual contacts"));
  EXPECT_TRUE(hand->eigengrasps.identity);
  EXPECT_TRUE(hand->virtualContacts.empty());
}

// A body whose mesh gives no inertia (GraspIt!'s rules: here a centroid 600 mm out) warns only
// where the inertia is used: as a graspable body, not as an obstacle.
TEST(GraspItLeniency, InertiaFallbackWarnsOnlyWhereUsed) {
  const fs::path folder = test::scratchDir();
  std::string off = "OFF\n8 12 0\n";
  for (int i = 0; i < 8; ++i)
    off += fmt::format("{} {} {}\n", 600 + 10 * (i & 1), 10 * ((i >> 1) & 1), 10 * (i >> 2));
  off +=
      "3 0 2 3\n3 0 3 1\n3 4 5 7\n3 4 7 6\n3 0 1 5\n3 0 5 4\n"
      "3 2 6 7\n3 2 7 3\n3 0 4 6\n3 0 6 2\n3 1 3 7\n3 1 7 5\n";
  std::ofstream(folder / "far.off") << off;
  std::ofstream(folder / "far.xml")
      << "<?xml version=\"1.0\" ?>\n<root>\n<material>wood</material>\n"
         "<geometryFile type=\"off\">far.off</geometryFile>\n</root>\n";
  for (const char* kind : {"obstacle", "graspableBody"}) {
    SCOPED_TRACE(kind);
    std::ofstream(folder / "world.xml")
        << "<?xml version=\"1.0\" ?>\n<world>\n<" << kind << ">\n<filename>far.xml</filename>\n</"
        << kind << ">\n</world>\n";
    const Warnings warnings;
    LoadOptions options;
    options.useEnvironment = false;
    const World world = loadWorldFile(folder / "world.xml", options);
    EXPECT_TRUE(world.bodies()[0].model->inertiaFallback);
    EXPECT_EQ(world.bodies()[0].model->inertia, Matrix3::Identity());
    if (std::string(kind) == "obstacle") {
      EXPECT_TRUE(warnings.texts.empty()) << ::testing::PrintToString(warnings.texts);
    } else {
      ASSERT_EQ(warnings.texts.size(), 1u) << ::testing::PrintToString(warnings.texts);
      EXPECT_NE(warnings.texts[0].find("world.xml:4: <filename>: the inertia of 'far'"),
                std::string::npos)
          << warnings.texts[0];
    }
  }
}

TEST(BadInputCorpus, EveryCorpusFileIsTested) {
  std::set<std::string> tested(kSupportFiles);
  for (const BadInput& input : kCorpus) tested.insert(input.path);
  for (const auto& entry : fs::recursive_directory_iterator(corpus())) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = fs::relative(entry.path(), corpus()).generic_string();
    EXPECT_TRUE(tested.count(relative)) << relative << " is in the corpus but not in the table";
  }
  for (const std::string& file : tested) {
    EXPECT_TRUE(fs::is_regular_file(corpus() / file)) << file;
  }
}

// The support files are valid, so each bad file fails for its own defect only.
TEST(BadInputCorpus, SupportFilesLoad) {
  auto hand = loadRobotFile(corpus() / "robots" / "good_hand.xml");
  EXPECT_EQ(hand->dofs.size(), 2u);
  EXPECT_EQ(hand->chains.size(), 1u);
  auto cube = loadBodyFile(corpus() / "bodies" / "good_cube.xml");
  EXPECT_EQ(cube->mesh->triangleCount(), 12u);
  EXPECT_EQ(cube->material, Material::Plastic);
  EXPECT_EQ(identityEigengrasps(3).grasps.size(), 3u);
  EXPECT_EQ(loadEigengraspFile(corpus() / "robots" / "eigen_wrong_dims.xml", 3).grasps.size(), 1u);
}

}  // namespace
}  // namespace graspkit
