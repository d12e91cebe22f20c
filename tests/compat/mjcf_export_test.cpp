// GraspIt!'s hands written as MJCF load in MuJoCo (Debian libmujoco-dev), and MuJoCo's forward
// kinematics puts every link body where graspkit puts the link (1e-6 mm, 1e-9 in the axes) at
// two joint vectors: the Barrett (coupled finger joints) and HumanHand20DOF (Universal links,
// whose first joint gets a body of its own).

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/mjcf/mjcf_export.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/io/urdf/urdf_export.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "quiet_warnings.hpp"
#include "reference.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

enum class Format { Mjcf, Urdf };

void expectMujocoAgrees(const std::string& file, Format format = Format::Mjcf) {
  SCOPED_TRACE(file);
  const auto model = loadRobotFile(*test::graspitDataDir() / file);
  // MuJoCo reads its own format, and URDF through its importer.
  const fs::path mjcf = format == Format::Mjcf ? saveMjcf(*model, test::scratchDir() / "mjcf")
                                               : saveUrdf(*model, test::scratchDir() / "urdf");
  char error[1000] = "";
  std::unique_ptr<mjModel, ModelDeleter> m(mj_loadXML(mjcf.c_str(), nullptr, error, sizeof(error)));
  ASSERT_TRUE(m) << "MuJoCo: " << error;
  std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m.get()));
  Robot robot(model);
  for (const double t : {0.3, 0.8}) {  // of each DOF's range
    SCOPED_TRACE(t);
    std::vector<double> values;
    for (const Dof& dof : model->dofs) values.push_back(dof.min + t * (dof.max - dof.min));
    robot.setDofValues(values);
    for (int j = 0; j < model->jointCount(); ++j) {
      const int id = mj_name2id(m.get(), mjOBJ_JOINT, ("joint" + std::to_string(j)).c_str());
      ASSERT_GE(id, 0) << "joint " << j;
      const double unit = model->joint(j).type == JointType::Prismatic ? 1000.0 : 1.0;
      d->qpos[m->jnt_qposadr[id]] = robot.jointValues()[j] / unit;
    }
    mj_kinematics(m.get(), d.get());
    int compared = 0;
    for (std::size_t c = 0; c < model->chains.size(); ++c) {
      for (std::size_t l = 0; l < model->chains[c].links.size(); ++l) {
        const std::string name = model->chains[c].links[l].name;
        const int body = mj_name2id(m.get(), mjOBJ_BODY, name.c_str());
        ASSERT_GE(body, 0) << name;
        const Transform& pose = robot.linkPose(static_cast<int>(c), static_cast<int>(l));
        const Vector3 position(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
        EXPECT_LT((1000.0 * position - pose.translation()).norm(), 1e-6) << name;
        Matrix3 axes;
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) axes(r, k) = d->xmat[9 * body + 3 * r + k];
        EXPECT_LT((axes - pose.linear()).norm(), 1e-9) << name;
        ++compared;
      }
    }
    EXPECT_EQ(compared, model->linkCount());
  }
}

TEST(MjcfExport, MujocoPlacesTheBarrettsLinksAsGraspkitDoes) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  expectMujocoAgrees("models/robots/Barrett/Barrett.xml");
}

TEST(MjcfExport, MujocoPlacesHumanHandUniversalLinksAsGraspkitDoes) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  expectMujocoAgrees("models/robots/HumanHand/HumanHand20DOF.xml");
}

// The URDF export loads in MuJoCo's URDF importer (its <mujoco><compiler meshdir> extension says
// where the meshes are) and MuJoCo's kinematics agree with graspkit's there too.
TEST(UrdfExport, MujocosUrdfImporterPlacesTheLinksAsGraspkitDoes) {
  GRASPKIT_REQUIRE_SHARED();
  test::QuietWarnings quiet;
  expectMujocoAgrees("models/robots/Barrett/Barrett.xml", Format::Urdf);
  expectMujocoAgrees("models/robots/HumanHand/HumanHand20DOF.xml", Format::Urdf);
}

}  // namespace
}  // namespace graspkit
