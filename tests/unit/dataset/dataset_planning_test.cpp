// A planned dataset replays: every grasp saved to a dataset file and read back, put into a world
// (hand closed as saved, breakaway states included), measured again, gives the epsilon, volume,
// force closure and contact count the dataset holds; the same request gives the same dataset,
// whether it loads the hand or is handed one loaded once for many objects.

#include <gtest/gtest.h>

#include "graspkit/dataset/dataset_planning.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/object_generator.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

DatasetRequest cylinderForTheBh8() {
  ObjectGeneratorOptions objects;
  objects.seed = 3;
  objects.kinds = {ObjectKind::Cylinder};
  const GeneratedObject cylinder = generateObject(objects, 0);
  BodyXmlOptions body;
  body.massGrams = cylinder.mass;
  DatasetRequest request;
  request.object = saveBodyFiles(test::scratchDir(), cylinder.name, cylinder.mesh, body);
  request.hand = test::modelsDir() / "robots/bh8/bh8.xml";
  request.grasps = 8;
  request.steps = 6000;
  request.seed = 4;
  return request;
}

TEST(DatasetPlanning, SavedGraspsReplayToTheSameQualities) {
  const DatasetRequest request = cylinderForTheBh8();
  const std::filesystem::path file = test::scratchDir() / "cylinder.h5";
  saveGraspDataset(planGraspDataset(request), file);
  const GraspDataset dataset = loadGraspDataset(file);
  ASSERT_EQ(dataset.grasps.size(), 8u);
  int broken_away = 0, force_closure = 0;
  for (std::size_t i = 0; i < dataset.grasps.size(); ++i) {
    SCOPED_TRACE(i);
    const DatasetGrasp& saved = dataset.grasps[i];
    const World world = datasetGraspWorld(request, saved);
    const Grasp again = analyzeGrasp(world, 0, BodyRef::body(0));
    EXPECT_EQ(again.forceClosure, saved.forceClosure);
    EXPECT_NEAR(again.epsilon, saved.epsilon, 1e-9);
    EXPECT_NEAR(again.volume, saved.volume, 1e-9 * std::max(1.0, saved.volume));
    EXPECT_EQ(again.contacts.size(), saved.contactPoints.size());
    for (const BreakawayState& state : saved.breakaway) broken_away += state.engaged ? 1 : 0;
    force_closure += saved.forceClosure ? 1 : 0;
  }
  // The case the breakaway states are saved for did occur (a finger whose distal joint went on
  // after its proximal link stopped), and some grasps hold.
  EXPECT_GT(broken_away, 0);
  EXPECT_GT(force_closure, 0);
}

TEST(DatasetPlanning, TheSameRequestGivesTheSameDataset) {
  const DatasetRequest request = cylinderForTheBh8();
  const GraspDataset a = planGraspDataset(request);
  const GraspDataset b = planGraspDataset(request);
  ASSERT_EQ(a.grasps.size(), b.grasps.size());
  for (std::size_t i = 0; i < a.grasps.size(); ++i) {
    EXPECT_EQ(a.grasps[i].grasp.matrix(), b.grasps[i].grasp.matrix());
    EXPECT_EQ(a.grasps[i].closedDofs, b.grasps[i].closedDofs);
    EXPECT_EQ(a.grasps[i].epsilon, b.grasps[i].epsilon);
  }
}

// graspkit batch loads the hand once and hands every object's request the loaded world: the
// datasets must be those of requests that load it themselves, and the shared world untouched.
TEST(DatasetPlanning, AHandLoadedOnceGivesTheDatasetOfOneLoadedPerRequest) {
  const DatasetRequest loading = cylinderForTheBh8();
  DatasetRequest shared = loading;
  shared.loadedHand = std::make_shared<const World>(loadAnyFile(loading.hand, loading.load));
  const GraspDataset a = planGraspDataset(loading);
  const GraspDataset b = planGraspDataset(shared);
  const GraspDataset c = planGraspDataset(shared);
  ASSERT_EQ(a.grasps.size(), b.grasps.size());
  ASSERT_EQ(a.grasps.size(), c.grasps.size());
  for (std::size_t i = 0; i < a.grasps.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(a.grasps[i].grasp.matrix(), b.grasps[i].grasp.matrix());
    EXPECT_EQ(a.grasps[i].closedDofs, b.grasps[i].closedDofs);
    EXPECT_EQ(a.grasps[i].epsilon, b.grasps[i].epsilon);
    EXPECT_EQ(b.grasps[i].grasp.matrix(), c.grasps[i].grasp.matrix());
  }
  EXPECT_TRUE(shared.loadedHand->bodies().empty());
  EXPECT_TRUE(shared.loadedHand->robot(0).pose().isApprox(Transform::Identity(), 0.0));
}

}  // namespace
}  // namespace graspkit
