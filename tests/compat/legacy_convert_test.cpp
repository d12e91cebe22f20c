// graspkit convert's engine side against GraspIt!'s own conversions: the legacy .vgr and .egr files
// of ../shared/graspit-data/legacy beside the XML files GraspIt! 2.1 ships for them, and a mesh's
// Body XML against the mass properties graspkit computes when the tags are absent.

#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/eigengrasp_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/legacy/legacy_files.hpp"
#include "quiet_warnings.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

// The .vgr files become, byte for byte, the XML GraspIt! ships for them.
TEST(LegacyConvert, VirtualContactFilesMatchGraspItsXmlExactly) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path data = *test::graspitDataDir();
  for (const char* name : {"Barrett/virtual/fingertips", "Barrett/virtual/all_16_contacts",
                           "HumanHand/virtual/all_18_contacts_20DOF"}) {
    SCOPED_TRACE(name);
    const std::string xml =
        virtualContactXmlFromVgr(data / "legacy/models/robots" / (std::string(name) + ".vgr"));
    EXPECT_EQ(xml, readText(data / "models/robots" / (std::string(name) + ".xml")));
  }
}

// The .egr files become eigengrasp XML that loads to what GraspIt!'s XML loads to: the same
// eigenvalues, directions and origin (GraspIt!'s files were edited by hand afterwards: comments,
// sparse DimVals, and limits the .egr files do not hold).
TEST(LegacyConvert, EigengraspFilesLoadAsGraspItsXml) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  const fs::path data = *test::graspitDataDir();
  const fs::path out = test::scratchDir();
  for (const auto& [name, dofs] : {std::pair{"Barrett/eigen/barrett_eigen", 4},
                                   std::pair{"HumanHand/eigen/human_eigen", 20}}) {
    SCOPED_TRACE(name);
    const fs::path converted = out / (fs::path(name).filename().string() + ".xml");
    writeText(converted,
              eigengraspXmlFromEgr(data / "legacy/models/robots" / (std::string(name) + ".egr")));
    const EigengraspSet mine = loadEigengraspFile(converted, dofs);
    const EigengraspSet theirs =
        loadEigengraspFile(data / "models/robots" / (std::string(name) + ".xml"), dofs);
    ASSERT_EQ(mine.grasps.size(), theirs.grasps.size());
    for (std::size_t g = 0; g < mine.grasps.size(); ++g) {
      EXPECT_EQ(mine.grasps[g].eigenValue, theirs.grasps[g].eigenValue);
      EXPECT_TRUE(mine.grasps[g].direction.isApprox(theirs.grasps[g].direction, 1e-15));
    }
    ASSERT_TRUE(mine.origin && theirs.origin);
    EXPECT_EQ(*mine.origin, *theirs.origin);
  }
}

// A mesh's Body XML holds the mass properties graspkit computes when the tags are absent, written
// so that they load back exactly; with a scale, those of the scaled mesh.
TEST(LegacyConvert, MeshBodyXmlLoadsToTheComputedMassProperties) {
  test::QuietWarnings quiet;
  const fs::path folder = test::scratchDir();
  fs::copy_file(test::modelsDir() / "objects" / "mug.iv", folder / "mug.iv");
  BodyXmlOptions options;
  options.material = Material::Glass;
  options.massGrams = 250;
  options.scale = 1.5;
  const std::string xml = bodyXmlForMesh(folder / "mug.iv", folder / "mug.xml", options);
  EXPECT_EQ(xml, bodyXmlForMesh(folder / "mug.iv", folder / "mug.xml",
                                options));  // the same bytes every time
  writeText(folder / "mug.xml", xml);
  const auto converted = loadBodyFile(folder / "mug.xml");
  writeText(folder / "plain.xml",
            "<?xml version=\"1.0\" ?>\n<root>\n<material>glass</material>\n<mass>250</mass>\n"
            "<geometryFile>mug.iv</geometryFile>\n<geometryScaling>1.5</geometryScaling>\n"
            "</root>\n");
  const auto computed = loadBodyFile(folder / "plain.xml");
  EXPECT_EQ(converted->material, Material::Glass);
  EXPECT_EQ(converted->mass, 250);
  EXPECT_EQ(converted->cog, computed->cog);
  EXPECT_EQ(converted->inertia, computed->inertia);
  EXPECT_EQ(converted->mesh->triangleCount(), computed->mesh->triangleCount());
  EXPECT_TRUE(converted->cogFromFile && converted->inertiaFromFile);
}

TEST(LegacyConvert, MalformedLegacyFilesNameFileAndLine) {
  const fs::path folder = test::scratchDir();
  writeText(folder / "bad.egr", "DIMENSIONS 2\nEG\n0.5\n1.0 nan\n");
  try {
    eigengraspXmlFromEgr(folder / "bad.egr");
    FAIL() << "a NaN converted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.egr:4"), std::string::npos) << e.what();
  }
  writeText(folder / "short.vgr", "Barrett\n2\n0 1\n8\n1 0 0\n");
  try {
    virtualContactXmlFromVgr(folder / "short.vgr");
    FAIL() << "a truncated file converted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("short.vgr:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the file ends"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace graspkit
