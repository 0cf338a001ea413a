#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "campaigns/run_record.hpp"

namespace thetad {

// Open MPI for a campaign run under `mpirun -np P thetad campaign run ...`. MPI is initialised only
// when mpirun (or srun with Open MPI's PMIx) started the process, so a plain `thetad` never needs an
// MPI runtime. Rank 0 hands out run indices and is the only writer; the other ranks fly the index
// they are given and send the record back with their next request (dynamic scheduling: a rank
// that flies a cheap or diverging run asks again sooner).
class MpiSession {
 public:
  // Whether this process was started by mpirun (OMPI_COMM_WORLD_SIZE or PMI_SIZE set).
  static bool launched_by_mpirun();

  MpiSession();  // MPI_Init_thread (funneled: only the main thread calls MPI)
  ~MpiSession();  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Rank 0: a request that arrived, if any (non-blocking). `record` holds the run the rank finished
  // with the request (none on its first request); `error` a failure it reports instead.
  struct Request {
    int rank = 0;
    std::optional<RunRecord> record;
    std::string error;
  };
  std::optional<Request> poll();
  // Rank 0: answers `rank` with the run index to fly next, or none: stop.
  void answer(int rank, std::optional<std::int64_t> index);

  // Other ranks: sends the finished record (or nothing) and waits for the next index (none: stop).
  std::optional<std::int64_t> request(const std::optional<RunRecord>& finished);
  // Other ranks: reports a failure to rank 0, which ends the campaign with it.
  void report_error(const std::string& message);

  // Ends every rank at once (rank 0 after an error, while the others wait on it).
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace thetad
