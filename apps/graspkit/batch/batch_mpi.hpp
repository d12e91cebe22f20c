#pragma once
// graspkit batch over MPI (Open MPI from Debian): `mpirun -np N graspkit batch ...` shares the
// objects out dynamically, one at a time to whichever rank is free (objects differ 50x in cost),
// and rank 0, which also plans, keeps the manifest. Built when CMake finds MPI.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "batch/batch_object.hpp"

namespace graspkit::cli {

// Whether an MPI launcher (mpirun, srun with PMI) started this process.
bool launchedByMpi();
// Whether this graspkit was built with MPI.
bool builtWithMpi();

// One batch's MPI session: MPI_Init when made, MPI_Finalize when gone.
class MpiBatch {
 public:
  MpiBatch();
  ~MpiBatch();
  MpiBatch(const MpiBatch&) = delete;
  MpiBatch& operator=(const MpiBatch&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Rank 0's word (go on, or stop after an error), the same on every rank.
  bool agree(bool go_on) const;

  using Work = std::function<ObjectOutcome(std::size_t object, const std::function<void()>& serve)>;
  using Record = std::function<void(std::size_t object, const ObjectOutcome& outcome)>;
  // Runs the `pending` objects (rank 0's list; the other ranks pass none) over every rank, rank 0
  // included: `work` plans one (calling `serve` while it waits, so that rank 0 keeps answering),
  // and on rank 0 `record` gets each outcome as it arrives. Returns when every object is done and
  // every rank has been told to stop.
  void run(const std::vector<std::size_t>& pending, const Work& work, const Record& record) const;

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace graspkit::cli
