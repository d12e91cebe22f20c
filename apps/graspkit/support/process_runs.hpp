#pragma once
// Whether a process still runs, for the commands that clean up after a killed run of their own:
// a temporary named with its writer's process id is stale once that process is gone.

#include <sys/types.h>

namespace graspkit::cli {

// A zombie (killed, not yet reaped by a container's init that may never reap it) does not run.
bool processRuns(pid_t pid);

}  // namespace graspkit::cli
