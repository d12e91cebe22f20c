#include "batch/batch_mpi.hpp"

#include <cstdlib>
#include <deque>

#include "graspkit/base/error.hpp"

#ifdef GRASPKIT_WITH_MPI
// The C interface only: Open MPI's deprecated C++ bindings would need their own library.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace graspkit::cli {

bool launchedByMpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(variable)) return true;
  return false;
}

#ifndef GRASPKIT_WITH_MPI

bool builtWithMpi() {
  return false;
}
MpiBatch::MpiBatch() {
  throw Error(
      "this graspkit was built without MPI (Debian libopenmpi-dev); run the ranks as --shard K/N "
      "instead");
}
MpiBatch::~MpiBatch() = default;
bool MpiBatch::agree(bool go_on) const {
  return go_on;
}
void MpiBatch::run(const std::vector<std::size_t>&, const Work&, const Record&) const {}

#else

namespace {

// Messages: a worker asks for work with kReady, carrying the JSON report of the object it has
// just planned ("" the first time); rank 0 answers kAssign with an object index, or kStop.
constexpr int kReady = 1;
constexpr int kAssign = 2;
constexpr long long kStop = -1;

struct Report {
  long long object = -1;
  ObjectOutcome outcome;
};

std::string reportText(std::size_t object, const ObjectOutcome& outcome) {
  nlohmann::json j = outcomeJson(outcome);
  j["object"] = object;
  return j.dump();
}

Report reportOf(const std::string& text) {
  Report report;
  if (text.empty()) return report;
  const auto j = nlohmann::json::parse(text);
  report.object = j.at("object").get<long long>();
  report.outcome = outcomeFromJson(j);
  return report;
}

// Rank 0's side: hands out the queue and records what comes back.
class Coordinator {
 public:
  Coordinator(std::deque<std::size_t> queue, int workers, const MpiBatch::Record& record)
      : queue_(std::move(queue)), workers_(workers), record_(record) {}

  // Answers every worker that is waiting; with `block`, waits for one first.
  void serve(bool block) {
    for (;;) {
      MPI_Status status;
      int waiting = 0;
      if (block) {
        MPI_Probe(MPI_ANY_SOURCE, kReady, MPI_COMM_WORLD, &status);
        waiting = 1;
        block = false;
      } else {
        MPI_Iprobe(MPI_ANY_SOURCE, kReady, MPI_COMM_WORLD, &waiting, &status);
      }
      if (!waiting) return;
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string text(static_cast<std::size_t>(length), '\0');
      MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kReady, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      const Report report = reportOf(text);
      if (report.object >= 0) record_(static_cast<std::size_t>(report.object), report.outcome);
      long long next = kStop;
      if (!queue_.empty()) {
        next = static_cast<long long>(queue_.front());
        queue_.pop_front();
      } else {
        --workers_;
      }
      MPI_Send(&next, 1, MPI_LONG_LONG, status.MPI_SOURCE, kAssign, MPI_COMM_WORLD);
    }
  }

  bool take(std::size_t& object) {
    if (queue_.empty()) return false;
    object = queue_.front();
    queue_.pop_front();
    return true;
  }
  bool workersLeft() const { return workers_ > 0; }

 private:
  std::deque<std::size_t> queue_;
  int workers_;
  const MpiBatch::Record& record_;
};

}  // namespace

bool builtWithMpi() {
  return true;
}

MpiBatch::MpiBatch() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiBatch::~MpiBatch() {
  MPI_Finalize();
}

bool MpiBatch::agree(bool go_on) const {
  int flag = go_on ? 1 : 0;
  MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return flag != 0;
}

void MpiBatch::run(const std::vector<std::size_t>& pending, const Work& work,
                   const Record& record) const {
  if (rank_ == 0) {
    Coordinator coordinator({pending.begin(), pending.end()}, size_ - 1, record);
    const std::function<void()> serve = [&] { coordinator.serve(false); };
    std::size_t object = 0;
    while (coordinator.take(object)) {
      serve();
      record(object, work(object, serve));
    }
    while (coordinator.workersLeft()) coordinator.serve(true);
    return;
  }
  std::string report;
  for (;;) {
    MPI_Send(report.data(), static_cast<int>(report.size()), MPI_CHAR, 0, kReady, MPI_COMM_WORLD);
    long long object = kStop;
    MPI_Recv(&object, 1, MPI_LONG_LONG, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (object == kStop) return;
    const auto index = static_cast<std::size_t>(object);
    report = reportText(index, work(index, {}));
  }
}

#endif

}  // namespace graspkit::cli
