#pragma once
// Grasp dataset files: the grasps planned on one object, in HDF5, laid out close to ACRONYM's
// per-object files so that dataset tools read them with little change. docs/dataset.md gives the
// layout; every length is in mm, every pose the hand's in the object's frame.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

// One direction of a grasp's physical validation (dynamics/grasp_validation.hpp's
// DirectionResult, without the failure's text): the object's weight turned along `direction`.
struct DatasetDirection {
  Vector3 direction = Vector3::Zero();  // unit, object frame: +x, -x, +y, -y, +z, -z in turn
  bool held = false;
  double slip = 0.0;     // mm: the largest displacement from the palm in the direction's run
  double turn = 0.0;     // rad: the largest rotation relative to the palm
  double seconds = 0.0;  // simulated: less than asked when the run ended at rest or let go
  bool failed = false;   // the simulation itself failed (its message is not kept)
  bool tried = true;     // false: an earlier direction let go and the validation stopped there
};

struct DatasetGrasp {
  Transform pregrasp = Transform::Identity();  // hand pose, open, in the object frame
  Transform grasp = Transform::Identity();     // hand pose, closed, in the object frame
  std::vector<double> openDofs;
  std::vector<double> closedDofs;
  // The closed hand's breakaway state, one per joint (robot-wide order): with the DOFs, what
  // places every link (a Barrett finger that broke away). Empty: no joint broke away.
  std::vector<BreakawayState> breakaway;
  double epsilon = -1.0;
  double volume = 0.0;
  bool forceClosure = false;
  int held = -1;  // dynamic validation: 1 held, 0 not, -1 not validated
  // The validation's 6 directions (empty when not validated); held is 1 when all held. A
  // validation that stops at the first direction let go leaves the rest not tried.
  std::vector<DatasetDirection> validation;
  // The closed hand's contacts on the object, object frame: points on its surface, and normals
  // pointing out of it.
  std::vector<Vector3> contactPoints;
  std::vector<Vector3> contactNormals;
};

struct GraspDataset {
  // The object's body file and the hand's robot file, as this process names them (relative to
  // the working folder, or absolute). The file stores them relative to its own folder, or
  // absolute (base/file_reference.hpp), and loadGraspDataset gives them back absolute, so a
  // dataset names its files from wherever it is read. (Schema 1 files stored them as batch was
  // given them; they come back as stored.)
  std::string objectFile;
  std::string objectName;
  double objectMass = 0.0;  // g
  std::string handFile;
  std::string handName;
  std::string engineVersion;
  std::uint64_t seed = 0;
  std::vector<DatasetGrasp> grasps;
};

// Writes `dataset` to `file` atomically (a temporary beside it, then a rename), with no
// timestamps, so the same dataset always gives the same bytes. Throws graspkit::Error naming the
// file when HDF5 cannot write it, or when grasps disagree on the DOF count.
void saveGraspDataset(const GraspDataset& dataset, const std::filesystem::path& file);

// Reads a file saveGraspDataset wrote. Throws graspkit::Error naming the file and the dataset
// for anything missing or malformed.
GraspDataset loadGraspDataset(const std::filesystem::path& file);

}  // namespace graspkit
