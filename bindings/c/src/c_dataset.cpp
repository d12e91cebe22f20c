// Grasp datasets: one object's planned as graspkit batch plans it, read and written as HDF5.

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/host/dataset_task.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

struct graspkit_dataset {
  GraspDataset dataset;
};

namespace {

const GraspDataset& datasetOf(const graspkit_dataset* dataset) {
  return require(dataset, "dataset")->dataset;
}

}  // namespace

extern "C" {

graspkit_status graspkit_dataset_options_default(graspkit_dataset_options* options) {
  return guarded([&] {
    const DatasetRequest defaults;
    graspkit_dataset_options& o = *require(options, "options");
    o = graspkit_dataset_options{};
    o.grasps = defaults.grasps;
    o.steps = host::kDefaultPlanSteps;
    o.seed = defaults.seed;
    o.validate = defaults.validate ? 1 : 0;
    o.validate_seconds = defaults.validateSeconds;
  });
}

graspkit_status graspkit_dataset_plan(const char* hand, const char* object,
                                      const graspkit_load_options* load,
                                      const graspkit_dataset_options* options,
                                      graspkit_dataset** dataset) {
  return guarded([&] {
    require(dataset, "dataset");
    graspkit_dataset_options o;
    graspkit_dataset_options_default(&o);
    if (options) o = *options;
    if (o.steps < 0)
      throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                    fmt::format("options->steps is {}: 0 (the default) or more", o.steps)};
    DatasetRequest request;
    request.hand = require(hand, "hand");
    request.object = require(object, "object");
    request.load = loadOptions(load);
    request.grasps = o.grasps;
    if (o.steps > 0) request.steps = o.steps;
    request.seed = o.seed;
    request.validate = o.validate != 0;
    request.validateSeconds = o.validate_seconds;
    auto result = std::make_unique<graspkit_dataset>();
    result->dataset = host::planDataset(request);
    *dataset = result.release();
  });
}

graspkit_status graspkit_dataset_load(const char* path, graspkit_dataset** dataset) {
  return guarded([&] {
    require(dataset, "dataset");
    auto result = std::make_unique<graspkit_dataset>();
    result->dataset = loadGraspDataset(require(path, "path"));
    *dataset = result.release();
  });
}

graspkit_status graspkit_dataset_save(const graspkit_dataset* dataset, const char* path) {
  return guarded([&] { saveGraspDataset(datasetOf(dataset), require(path, "path")); });
}

graspkit_status graspkit_dataset_count(const graspkit_dataset* dataset, size_t* count) {
  return guarded([&] { *require(count, "count") = datasetOf(dataset).grasps.size(); });
}

graspkit_status graspkit_dataset_get_grasp(const graspkit_dataset* dataset, size_t index,
                                           graspkit_dataset_grasp* grasp) {
  return guarded([&] {
    const GraspDataset& d = datasetOf(dataset);
    if (index >= d.grasps.size())
      throw Failure{
          GRASPKIT_ERROR_OUT_OF_RANGE,
          fmt::format("grasp {} does not exist (the dataset has {})", index, d.grasps.size())};
    const DatasetGrasp& g = d.grasps[index];
    graspkit_dataset_grasp& out = *require(grasp, "grasp");
    out.pregrasp = toPose(g.pregrasp);
    out.grasp = toPose(g.grasp);
    out.epsilon = g.epsilon;
    out.volume = g.volume;
    out.force_closure = g.forceClosure ? 1 : 0;
    out.held = g.held;
    out.contacts = static_cast<std::int32_t>(g.contactPoints.size());
  });
}

void graspkit_dataset_free(graspkit_dataset* dataset) {
  delete dataset;
}

}  // extern "C"
