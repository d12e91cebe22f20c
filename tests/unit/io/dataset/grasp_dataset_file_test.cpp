// Grasp dataset files: what is saved loads back equal, field for field (the validation's six
// directions included); saving again gives the same bytes; the object and hand files are named
// from wherever the file is read; an empty dataset is a valid file; a schema 1 file still reads;
// a file that is not one is refused with its name.

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

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
  a.held = 0;  // let go in one direction
  const Vector3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int k = 0; k < 6; ++k) {
    DatasetDirection direction;
    direction.direction = axes[k];
    direction.held = k != 3;
    direction.slip = k == 3 ? 41.25 : 0.125 * (k + 1);
    direction.turn = 0.001 * (k + 1);
    direction.seconds = k == 3 ? 0.6875 : 2.0 - 0.25 * k;
    direction.failed = k == 5;
    a.validation.push_back(direction);
  }
  a.contactPoints = {{1, 2, 3}, {4, 5, 6}, {-7, 8.5, 9}};
  a.contactNormals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  DatasetGrasp b;  // no contacts, not validated
  b.grasp = pose(2.0, {0, 1, 0}, {0, 0, 200});
  b.openDofs = {0, 0, 0, 0};
  b.closedDofs = {0.2, 0.2, 0.2, 0};
  d.grasps = {a, b};
  return d;
}

// Sets a saved file's schema_version attribute, as an older graspkit would have written it.
void rewriteSchemaVersion(const fs::path& file, int version) {
  const hid_t h = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  const hid_t attr = H5Aopen(h, "schema_version", H5P_DEFAULT);
  EXPECT_GE(H5Awrite(attr, H5T_NATIVE_INT, &version), 0);
  H5Aclose(attr);
  H5Fclose(h);
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
  // Files come back absolute, naming what the saved (working-folder-relative) names named.
  EXPECT_TRUE(fs::path(loaded.objectFile).is_absolute()) << loaded.objectFile;
  EXPECT_EQ(fs::weakly_canonical(loaded.objectFile),
            fs::weakly_canonical(fs::absolute(saved.objectFile)));
  EXPECT_EQ(loaded.objectName, saved.objectName);
  EXPECT_EQ(loaded.objectMass, saved.objectMass);
  EXPECT_EQ(fs::weakly_canonical(loaded.handFile),
            fs::weakly_canonical(fs::absolute(saved.handFile)));
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
    ASSERT_EQ(l.validation.size(), s.validation.size());
    for (std::size_t k = 0; k < s.validation.size(); ++k) {
      EXPECT_EQ(l.validation[k].direction, s.validation[k].direction) << k;
      EXPECT_EQ(l.validation[k].held, s.validation[k].held) << k;
      EXPECT_EQ(l.validation[k].slip, s.validation[k].slip) << k;
      EXPECT_EQ(l.validation[k].turn, s.validation[k].turn) << k;
      EXPECT_EQ(l.validation[k].seconds, s.validation[k].seconds) << k;
      EXPECT_EQ(l.validation[k].failed, s.validation[k].failed) << k;
      EXPECT_TRUE(l.validation[k].tried) << k;
    }
  }
  EXPECT_EQ(loaded.grasps[0].validation.size(), 6u);
  EXPECT_TRUE(loaded.grasps[1].validation.empty());  // not validated
  // The same dataset, saved again, is the same file.
  const fs::path again = test::scratchDir() / "two_grasps_again.h5";
  saveGraspDataset(saved, again);
  EXPECT_EQ(bytesOf(again), bytesOf(file));
}

// Runs `body` with the working folder at `folder`, restoring it afterwards.
template <class F>
void inFolder(const fs::path& folder, F body) {
  const fs::path before = fs::current_path();
  fs::current_path(folder);
  try {
    body();
  } catch (...) {
    fs::current_path(before);
    throw;
  }
  fs::current_path(before);
}

TEST(GraspDatasetFile, DirectionsAfterTheFirstLetGoLoadBackUntried) {
  // A batch validation stops at the first direction the grasp lets go (here the second): the
  // four after it were not tried, and must not load back as "let go".
  GraspDataset saved = twoGrasps();
  std::vector<DatasetDirection>& directions = saved.grasps[0].validation;
  directions[1].held = false;
  for (std::size_t k = 2; k < 6; ++k) directions[k] = {directions[k].direction};
  for (std::size_t k = 2; k < 6; ++k) directions[k].tried = false;
  const fs::path file = test::scratchDir() / "stopped.h5";
  saveGraspDataset(saved, file);
  const GraspDataset loaded = loadGraspDataset(file);
  ASSERT_EQ(loaded.grasps[0].validation.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    const DatasetDirection& d = loaded.grasps[0].validation[k];
    EXPECT_EQ(d.tried, k < 2) << k;
    EXPECT_EQ(d.held, k == 0) << k;
    EXPECT_EQ(d.direction, directions[k].direction) << k;
    EXPECT_EQ(d.slip, directions[k].slip) << k;
  }
  EXPECT_EQ(loaded.grasps[0].held, 0);
  EXPECT_TRUE(loaded.grasps[1].validation.empty());
  // A schema 2 file had no untried directions: -1 there is an error that names the element.
  rewriteSchemaVersion(file, 2);
  try {
    loadGraspDataset(file);
    ADD_FAILURE() << "a schema 2 file with an untried direction loaded";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/grasps/validation/held"), std::string::npos)
        << error.what();
  }
}

TEST(GraspDatasetFile, AnyDirectionMayBeTheOneTried) {
  // The six pulls take their steps by turns, so the one let go can be any of them, and +x can
  // be among those cut short. Such a grasp read back as not validated at all.
  GraspDataset saved = twoGrasps();
  std::vector<DatasetDirection>& directions = saved.grasps[0].validation;
  for (std::size_t k = 0; k < 6; ++k) {
    if (k == 3) continue;
    directions[k] = {directions[k].direction};
    directions[k].tried = false;
  }
  directions[3].held = false;
  saved.grasps[0].held = 0;
  const fs::path file = test::scratchDir() / "minus_y_let_go.h5";
  saveGraspDataset(saved, file);
  const GraspDataset loaded = loadGraspDataset(file);
  ASSERT_EQ(loaded.grasps[0].validation.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    const DatasetDirection& d = loaded.grasps[0].validation[k];
    EXPECT_EQ(d.tried, k == 3) << k;
    EXPECT_FALSE(d.held) << k;
    EXPECT_EQ(d.slip, directions[k].slip) << k;
    EXPECT_EQ(d.seconds, directions[k].seconds) << k;
  }
  EXPECT_EQ(loaded.grasps[0].held, 0);
  // A validation with nothing tried could only read back as none: it is refused when saved.
  directions[3].tried = false;
  EXPECT_THROW(saveGraspDataset(saved, test::scratchDir() / "nothing_tried.h5"), Error);
}

TEST(GraspDatasetFile, NamesItsFilesFromAnyWorkingFolder) {
  // A project with its objects and a dataset folder; the dataset is written from the project's
  // folder with the names batch gives (relative to it), and read from elsewhere.
  const fs::path project = test::scratchDir();
  fs::create_directories(project / "objects");
  fs::create_directories(project / "out" / "grasps");
  std::ofstream(project / "objects" / "box.xml") << "<root/>\n";
  std::ofstream(project / "hand.xml") << "<robot/>\n";
  GraspDataset saved = twoGrasps();
  saved.objectFile = "objects/box.xml";
  saved.handFile = "hand.xml";
  inFolder(project, [&] { saveGraspDataset(saved, "out/grasps/box.h5"); });
  const fs::path elsewhere = test::scratchDir();
  inFolder(elsewhere, [&] {
    const GraspDataset loaded = loadGraspDataset(project / "out" / "grasps" / "box.h5");
    EXPECT_TRUE(fs::equivalent(loaded.objectFile, project / "objects" / "box.xml"))
        << loaded.objectFile;
    EXPECT_TRUE(fs::equivalent(loaded.handFile, project / "hand.xml")) << loaded.handFile;
  });
  // The project moved as a whole: the dataset still names its object.
  const fs::path moved = test::scratchDir() / "moved";
  fs::rename(project, moved);
  const GraspDataset loaded = loadGraspDataset(moved / "out" / "grasps" / "box.h5");
  EXPECT_TRUE(fs::equivalent(loaded.objectFile, moved / "objects" / "box.xml"))
      << loaded.objectFile;
}

TEST(GraspDatasetFile, SchemaOneFilesStillRead) {
  // A file as graspkit wrote it before schema 2: no /grasps/validation, names as given.
  const fs::path file = test::scratchDir() / "schema1.h5";
  GraspDataset saved = twoGrasps();
  saved.objectFile = "/data/objects/object_0001_cylinder.xml";
  saveGraspDataset(saved, file);
  const hid_t h = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  EXPECT_GE(H5Ldelete(h, "/grasps/validation", H5P_DEFAULT), 0);
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, H5T_VARIABLE);
  H5Tset_cset(text, H5T_CSET_UTF8);
  const hid_t hand = H5Dopen2(h, "/hand/file", H5P_DEFAULT);
  const char* as_given = "models/robots/Barrett/Barrett.xml";
  EXPECT_GE(H5Dwrite(hand, text, H5S_ALL, H5S_ALL, H5P_DEFAULT, &as_given), 0);
  H5Dclose(hand);
  H5Tclose(text);
  H5Fclose(h);
  rewriteSchemaVersion(file, 1);
  const GraspDataset loaded = loadGraspDataset(file);
  ASSERT_EQ(loaded.grasps.size(), 2u);
  EXPECT_EQ(loaded.grasps[0].held, 0);
  EXPECT_TRUE(loaded.grasps[0].validation.empty());
  EXPECT_EQ(loaded.grasps[0].epsilon, saved.grasps[0].epsilon);
  EXPECT_EQ(loaded.handFile, "models/robots/Barrett/Barrett.xml");  // as stored
  EXPECT_EQ(loaded.objectFile, "/data/objects/object_0001_cylinder.xml");
}

TEST(GraspDatasetFile, AValidationRowThatIsNotABooleanIsRefused) {
  const fs::path file = test::scratchDir() / "bad_validation.h5";
  saveGraspDataset(twoGrasps(), file);
  const hid_t h = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(h, 0);
  const hid_t set = H5Dopen2(h, "/grasps/validation/held", H5P_DEFAULT);
  std::int8_t held[12] = {1, 1, 7, 1, 1, 1, -1, -1, -1, -1, -1, -1};
  EXPECT_GE(H5Dwrite(set, H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, held), 0);
  H5Dclose(set);
  H5Fclose(h);
  try {
    loadGraspDataset(file);
    ADD_FAILURE() << "loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_NE(std::string(e.what()).find("/grasps/validation/held"), std::string::npos) << e.what();
  }
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
