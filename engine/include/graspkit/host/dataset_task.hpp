#pragma once
// One object's grasp dataset as every front end plans it: dataset/dataset_planning.hpp's request
// with the host layer's default budget.

#include "graspkit/dataset/dataset_planning.hpp"

namespace graspkit::host {

// planGraspDataset(request), with kDefaultPlanSteps when the request gives neither steps nor
// seconds. Throws graspkit::Error as planGraspDataset does.
GraspDataset planDataset(DatasetRequest request);

}  // namespace graspkit::host
