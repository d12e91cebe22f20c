// Grasp dataset files: what is saved loads back equal, field for field; saving again gives the
// same bytes; an empty dataset is a valid file; a file that is not one is refused with its name.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "graspkit/base/error.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

Transform pose(double angle, const Vector3& axis, const Vector3& at) {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(angle, axis.normalized()));
  t.translation() = at;
  return t;
}

GraspDataset twoGrasps() {
  GraspDataset d;
  d.objectFile = "out/objects/object_0001_cylinder.xml";
  d.objectName = "object_0001_cylinder";
  d.objectMass = 122.06431453564339;
  d.handFile = "models/robots/Barrett/Barrett.xml";
  d.handName = "Barrett";
  d.engineVersion = "0.1.0";
  d.seed = 18446744073709551557ull;  // beyond int64: the attribute is unsigned
  DatasetGrasp a;
  a.pregrasp = pose(0.3, {1, 2, 3}, {10, -20, 130.5});
  a.grasp = pose(0.31, {1, 2, 3}, {11, -19, 120.25});
  a.openDofs = {0, 0, 0, 0.1};
  a.closedDofs = {0.5, 1.2, 1.3, 0.1};
  a.breakaway = {{false, 0.0}, {true, 0.75}, {false, 0.0}};
  a.epsilon = 0.16891;
  a.volume = 0.10569;
  a.forceClosure = true;
  a.held = 1;
  a.contactPoints = {{1, 2, 3}, {4, 5, 6}, {-7, 8.5, 9}};
  a.contactNormals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  DatasetGrasp b;  // no contacts, not validated
  b.grasp = pose(2.0, {0, 1, 0}, {0, 0, 200});
  b.openDofs = {0, 0, 0, 0};
  b.closedDofs = {0.2, 0.2, 0.2, 0};
  d.grasps = {a, b};
  return d;
}

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(GraspDatasetFile, LoadsBackWhatWasSaved) {
  const fs::path file = test::scratchDir() / "two_grasps.h5";
  const GraspDataset saved = twoGrasps();
  saveGraspDataset(saved, file);
  const GraspDataset loaded = loadGraspDataset(file);
  EXPECT_EQ(loaded.objectFile, saved.objectFile);
  EXPECT_EQ(loaded.objectName, saved.objectName);
  EXPECT_EQ(loaded.objectMass, saved.objectMass);
  EXPECT_EQ(loaded.handFile, saved.handFile);
  EXPECT_EQ(loaded.handName, saved.handName);
  EXPECT_EQ(loaded.engineVersion, saved.engineVersion);
  EXPECT_EQ(loaded.seed, saved.seed);
  ASSERT_EQ(loaded.grasps.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const DatasetGrasp& s = saved.grasps[i];
    const DatasetGrasp& l = loaded.grasps[i];
    EXPECT_EQ(l.grasp.matrix(), s.grasp.matrix());
    EXPECT_EQ(l.pregrasp.matrix(), s.pregrasp.matrix());
    EXPECT_EQ(l.openDofs, s.openDofs);
    EXPECT_EQ(l.closedDofs, s.closedDofs);
    ASSERT_EQ(l.breakaway.size(), 3u);  // b saved none: three joints, none broken away
    for (std::size_t j = 0; j < 3; ++j) {
      const BreakawayState expected = s.breakaway.empty() ? BreakawayState{} : s.breakaway[j];
      EXPECT_EQ(l.breakaway[j].engaged, expected.engaged);
      EXPECT_EQ(l.breakaway[j].value, expected.value);
    }
    EXPECT_EQ(l.epsilon, s.epsilon);
    EXPECT_EQ(l.volume, s.volume);
    EXPECT_EQ(l.forceClosure, s.forceClosure);
    EXPECT_EQ(l.held, s.held);
    EXPECT_EQ(l.contactPoints, s.contactPoints);
    EXPECT_EQ(l.contactNormals, s.contactNormals);
  }
  // The same dataset, saved again, is the same file.
  const fs::path again = test::scratchDir() / "two_grasps_again.h5";
  saveGraspDataset(saved, again);
  EXPECT_EQ(bytesOf(again), bytesOf(file));
}

TEST(GraspDatasetFile, AnObjectWithNoGraspsIsAValidFile) {
  const fs::path file = test::scratchDir() / "no_grasps.h5";
  GraspDataset empty = twoGrasps();
  empty.grasps.clear();
  saveGraspDataset(empty, file);
  const GraspDataset loaded = loadGraspDataset(file);
  EXPECT_TRUE(loaded.grasps.empty());
  EXPECT_EQ(loaded.objectName, empty.objectName);
}

TEST(GraspDatasetFile, BadFilesAndDatasetsAreRefused) {
  const fs::path text = test::scratchDir() / "not_hdf5.h5";
  std::ofstream(text) << "not an HDF5 file\n";
  try {
    loadGraspDataset(text);
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, text.string());
  }
  EXPECT_THROW(loadGraspDataset(test::scratchDir() / "nowhere.h5"), Error);
  GraspDataset uneven = twoGrasps();
  uneven.grasps[1].openDofs.push_back(0.0);
  const fs::path file = test::scratchDir() / "uneven.h5";
  EXPECT_THROW(saveGraspDataset(uneven, file), Error);
  EXPECT_FALSE(fs::exists(file));  // nothing half written
}

}  // namespace
}  // namespace graspkit
