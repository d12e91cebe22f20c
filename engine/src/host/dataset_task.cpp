#include "graspkit/host/dataset_task.hpp"

#include "graspkit/host/plan_task.hpp"

namespace graspkit::host {

GraspDataset planDataset(DatasetRequest request) {
  if (!request.steps && !request.seconds) request.steps = kDefaultPlanSteps;
  return planGraspDataset(request);
}

}  // namespace graspkit::host
