// Every robot of the GraspIt! corpus written as URDF (and as GraspIt! XML) and read back: the same
// DOFs and chains, the same triangles on every link, and the same link poses (1e-6 mm, 1e-9 in the
// axes) at GraspIt!'s reference DOF vectors and at each robot's zero, lower, middle and upper DOF
// vectors. A DOF's value read back is scaled by its first joint's coupling ratio (the URDF
// joint that carries the DOF turns by the joint's angle).

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/urdf/urdf_export.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "quiet_warnings.hpp"
#include "reference.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::vector<double>> dofVectors(const RobotModel& model, const std::string& file) {
  std::vector<std::vector<double>> vectors;
  const json& figures = test::referenceJson().at("forward_kinematics");
  if (figures.contains(file)) {
    for (const auto& [name, config] : figures.at(file).at("configs").items())
      vectors.push_back(config.at("state").at("dof_values").get<std::vector<double>>());
  }
  for (const double t : {-1.0, 0.0, 0.5, 1.0}) {  // -1: zero; else min + t (max - min)
    std::vector<double> values;
    for (const Dof& dof : model.dofs)
      values.push_back(t < 0.0 ? dof.clamp(0.0) : dof.min + t * (dof.max - dof.min));
    vectors.push_back(values);
  }
  return vectors;
}

// Every link of `before` where the same link of `after` is: 1e-6 mm, 1e-9 in the axes.
void expectSamePoses(const Robot& before, const Robot& after) {
  const auto& a = before.linkPoses();
  const auto& b = after.linkPoses();
  for (std::size_t c = 0; c < a.size(); ++c) {
    for (std::size_t l = 0; l < a[c].size(); ++l) {
      EXPECT_LT((a[c][l].translation() - b[c][l].translation()).norm(), 1e-6)
          << "chain " << c << " link " << l;
      EXPECT_LT((a[c][l].linear() - b[c][l].linear()).norm(), 1e-9)
          << "chain " << c << " link " << l;
    }
  }
}

TEST(UrdfRoundTrip, EveryCorpusRobotKeepsItsLinksAndPoses) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  const fs::path data = *test::graspitDataDir();
  const fs::path out = test::scratchDir();
  int checked = 0;
  for (const json& entry : test::referenceJson().at("robot_survey_shared")) {
    if (!entry.at("load_ok").get<bool>()) continue;
    const std::string file = entry.at("file");
    SCOPED_TRACE(file);
    const auto original = loadRobotFile(data / file);
    const fs::path urdf = saveUrdf(*original, out / fs::path(file).stem());
    const auto back = loadUrdfFile(urdf);
    ASSERT_EQ(back->dofs.size(), original->dofs.size());
    ASSERT_EQ(back->chains.size(), original->chains.size());
    EXPECT_EQ(back->palm->mesh->triangleCount(), original->palm->mesh->triangleCount());
    for (std::size_t c = 0; c < original->chains.size(); ++c) {
      ASSERT_EQ(back->chains[c].links.size(), original->chains[c].links.size()) << "chain " << c;
      ASSERT_EQ(back->chains[c].joints.size(), original->chains[c].joints.size()) << "chain " << c;
      for (std::size_t l = 0; l < original->chains[c].links.size(); ++l) {
        EXPECT_EQ(back->chains[c].links[l].body->mesh->triangleCount(),
                  original->chains[c].links[l].body->mesh->triangleCount());
        EXPECT_EQ(back->chains[c].links[l].lastJoint, original->chains[c].links[l].lastJoint);
      }
    }
    Robot before(original), after(back);
    for (const std::vector<double>& values : dofVectors(*original, file)) {
      before.setDofValues(values);
      std::vector<double> scaled(values.size());
      for (std::size_t d = 0; d < values.size(); ++d) {
        const Dof& dof = original->dofs[d];
        scaled[d] = dof.joints.empty()
                        ? 0.0
                        : original->joint(dof.joints.front()).ratio * before.dofValues()[d];
      }
      after.setDofValues(scaled, LimitPolicy::Ignore);
      expectSamePoses(before, after);
    }
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// Written back as GraspIt! XML (robot file, body files, OFF meshes), every corpus robot reads
// back with the same DOFs, links, triangles and link poses at the same DOF vectors.
TEST(GraspitRobotRoundTrip, EveryCorpusRobotKeepsItsLinksAndPoses) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  const fs::path data = *test::graspitDataDir();
  const fs::path out = test::scratchDir();
  int checked = 0;
  for (const json& entry : test::referenceJson().at("robot_survey_shared")) {
    if (!entry.at("load_ok").get<bool>()) continue;
    const std::string file = entry.at("file");
    SCOPED_TRACE(file);
    const auto original = loadRobotFile(data / file);
    const auto back = loadRobotFile(saveRobotFile(*original, out / fs::path(file).stem()));
    ASSERT_EQ(back->dofs.size(), original->dofs.size());
    ASSERT_EQ(back->chains.size(), original->chains.size());
    EXPECT_EQ(back->triangleCount(), original->triangleCount());
    EXPECT_EQ(back->type, original->type);
    for (std::size_t c = 0; c < original->chains.size(); ++c)
      ASSERT_EQ(back->chains[c].links.size(), original->chains[c].links.size());
    Robot before(original), after(back);
    for (const std::vector<double>& values : dofVectors(*original, file)) {
      before.setDofValues(values);
      after.setDofValues(values);
      expectSamePoses(before, after);
    }
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

}  // namespace
}  // namespace graspkit
