// Exporters given names from someone else's file: a robot named like a path must not write
// outside the output folder, and a name holding XML's special characters must come back from
// the written file as it went in (no injected attribute, no broken comment). Also the output
// rule shared by every writer: only a regular file is ever replaced.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <tinyxml2.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/mjcf/mjcf_export.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/io/urdf/urdf_export.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "io/common/export_text.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// A one-DOF gripper whose robot name is `name` (written here XML-escaped by hand).
std::string gripper(const std::string& escaped_name) {
  return R"(<?xml version="1.0"?>
<robot name=")" +
         escaped_name + R"(">
  <link name="palm"><collision><geometry><box size="0.08 0.04 0.02"/></geometry></collision></link>
  <link name="left">
    <collision><origin xyz="0 0 0.02"/><geometry><box size="0.01 0.02 0.04"/></geometry></collision>
  </link>
  <joint name="slide" type="prismatic">
    <parent link="palm"/><child link="left"/><origin xyz="-0.03 0 0.01"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.025" effort="20" velocity="0.1"/>
  </joint>
</robot>
)";
}

// Every regular file under `folder`.
std::vector<fs::path> filesUnder(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) out.push_back(entry.path());
  return out;
}

std::string rootAttribute(const fs::path& file, const char* attribute) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(file.c_str()), tinyxml2::XML_SUCCESS) << file;
  const tinyxml2::XMLElement* root = doc.RootElement();
  const char* value = root ? root->Attribute(attribute) : nullptr;
  return value ? value : "(none)";
}

struct Hostile {
  std::string name;     // as the robot is named in memory
  std::string escaped;  // as written in the test's URDF
};

TEST(ExportNames, PathLikeRobotNamesStayInsideTheOutputFolder) {
  const fs::path base = test::scratchDir() / "export_paths";
  const fs::path victim = base / "victim";
  fs::create_directories(victim);
  std::ofstream(victim / "important.urdf") << "keep";
  std::ofstream(victim / "important.xml") << "keep";
  for (const std::string& name :
       {(victim / "important").string(), std::string("../victim/important"), std::string(".."),
        std::string("..."), std::string("a/b/c")}) {
    const fs::path input = base / "in.urdf";
    std::ofstream(input) << gripper(io::xmlEscaped(name));
    const auto model = loadUrdfFile(input);
    ASSERT_EQ(model->name, name);
    const fs::path out = base / "out";
    fs::remove_all(out);
    for (const fs::path& written :
         {saveUrdf(*model, out), saveMjcf(*model, out), saveRobotFile(*model, out)}) {
      EXPECT_EQ(written.parent_path(), out) << written;
    }
    // Nothing beside the output folder was created, nothing in the victim's folder either.
    EXPECT_EQ(filesUnder(base).size(), filesUnder(out).size() + 3) << name;
    std::ifstream a(victim / "important.urdf"), b(victim / "important.xml");
    std::string ta, tb;
    a >> ta;
    b >> tb;
    EXPECT_EQ(ta, "keep") << name;
    EXPECT_EQ(tb, "keep") << name;
    // The written URDF loads back with the robot's own name.
    EXPECT_EQ(loadUrdfFile(saveUrdf(*model, out))->name, name);
  }
}

TEST(ExportNames, SpecialCharactersInNamesComeBackAsTheyWentIn) {
  const fs::path base = test::scratchDir() / "export_xml";
  const std::vector<Hostile> names = {
      {"\" onload=\"alert(1)", "&quot; onload=&quot;alert(1)"},
      {"a<b>&c'd", "a&lt;b&gt;&amp;c&apos;d"},
      {"end --> <!-- x", "end --&gt; &lt;!-- x"},
  };
  for (const Hostile& h : names) {
    // The input file's own name breaks a naive header comment too.
    const fs::path input = base / "hand--v2-.urdf";
    fs::create_directories(base);
    std::ofstream(input) << gripper(h.escaped);
    const auto model = loadUrdfFile(input);
    ASSERT_EQ(model->name, h.name);
    const fs::path out = base / "out";
    fs::remove_all(out);
    const fs::path urdf = saveUrdf(*model, out);
    EXPECT_EQ(rootAttribute(urdf, "name"), h.name);
    EXPECT_EQ(loadUrdfFile(urdf)->name, h.name);
    const fs::path mjcf = saveMjcf(*model, out);
    EXPECT_EQ(rootAttribute(mjcf, "model"), h.name);
    const fs::path graspit = saveRobotFile(*model, out);
    EXPECT_NO_THROW(loadRobotFile(graspit)) << h.name;
  }
}

TEST(ExportNames, ControlCharactersBecomeQuestionMarksAndFileStemsAreSafe) {
  EXPECT_EQ(io::xmlEscaped(std::string("a\x01"
                                       "b\x7f")),
            "a?b?");
  EXPECT_EQ(io::xmlEscaped("tab\there"), "tab&#9;here");
  EXPECT_EQ(io::xmlCommentText("a--b-"), "a- -b- ");
  EXPECT_EQ(io::xmlCommentText("---"), "- - - ");
  EXPECT_EQ(io::fileStem("../../etc/passwd", "robot"), "_.._etc_passwd");
  EXPECT_EQ(io::fileStem("/abs/victim", "robot"), "_abs_victim");
  EXPECT_EQ(io::fileStem("..", "robot"), "robot");
  EXPECT_EQ(io::fileStem("", "robot"), "robot");
  EXPECT_EQ(io::fileStem("Barrett-BH8.v2", "robot"), "Barrett-BH8.v2");
  EXPECT_EQ(io::fileStem(std::string(300, 'x'), "robot").size(), 100u);
}

TEST(OutputFile, OnlyRegularFilesAreReplaced) {
  const fs::path base = test::scratchDir() / "output_special";
  fs::create_directories(base);
  const fs::path fifo = base / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_THROW(writeFileAtomically(fifo, "x"), Error);
  EXPECT_TRUE(fs::is_fifo(fifo));
  fs::create_directories(base / "folder");
  EXPECT_THROW(writeFileAtomically(base / "folder", "x"), Error);
  EXPECT_TRUE(fs::is_directory(base / "folder"));
  // A device (read-only check as any user: the error comes before any write).
  try {
    writeFileAtomically("/dev/null", "x");
    ADD_FAILURE() << "replaced /dev/null";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a device"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A symlink to a FIFO is the FIFO; a symlink to a regular file is replaced as before.
  fs::create_symlink(fifo, base / "link_to_pipe");
  EXPECT_THROW(writeFileAtomically(base / "link_to_pipe", "x"), Error);
  writeFileAtomically(base / "plain.txt", "one");
  writeFileAtomically(base / "plain.txt", "two");
  std::ifstream in(base / "plain.txt");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "two");
}

}  // namespace
}  // namespace graspkit
