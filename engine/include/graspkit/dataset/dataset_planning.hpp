#pragma once
// One object's grasp dataset (io/grasp_dataset_file.hpp), planned: the hand over the object at
// the origin, simann on GraspIt!'s contact energy, the best grasps closed and measured, and
// optionally validated physically. What graspkit batch runs for each object, for hosts that
// build datasets their own way.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

struct DatasetRequest {
  std::filesystem::path hand;    // a robot file
  std::filesystem::path object;  // a body file
  LoadOptions load;
  // `hand` as loadAnyFile(hand, load) gives it, loaded once for the requests of many objects
  // (graspkit batch loads it before forking each object's process, whose collision hierarchies
  // are then built once). Empty: `hand` is loaded for this request.
  std::shared_ptr<const World> loadedHand;
  int grasps = 20;                    // the best list's size
  std::optional<std::int64_t> steps;  // the planner's budget: steps (reproducible) ...
  std::optional<double> seconds;      // ... or wall time
  bool validate = false;              // label each grasp (grasp_validation.hpp)
  double validateSeconds = 2.0;
  // False: a grasp's validation ends at the first direction it lets go
  // (ValidationRequest::allDirections), the others stored as not tried. The held label is the
  // same; most planned grasps fail, and the pulls they hold were most of validation's time.
  bool validateAllDirections = false;
  // True: a direction statics shows held ends after a short probe instead of running until it
  // rests (ValidationRequest::statics): the same labels, measured on planned grasps
  // (docs/dynamics.md), in less time. Its slip, turn and seconds are the probe's.
  bool validateStatics = false;
  std::uint64_t seed = 1;
};

// Plans the dataset of one object on one thread: the same request gives the same dataset.
// Throws graspkit::Error for files that do not load or a request without a budget.
GraspDataset planGraspDataset(const DatasetRequest& request);

// The world a dataset grasp stands for: the hand (robot 0) closed as the grasp left it, breakaway
// states included, over the object (body 0) at the origin. Measured again (analyzeGrasp), it
// gives the grasp's epsilon and volume.
World datasetGraspWorld(const DatasetRequest& request, const DatasetGrasp& grasp);

}  // namespace graspkit
