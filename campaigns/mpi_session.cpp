#include "campaigns/mpi_session.hpp"

#include <mpi.h>

#include <cstdlib>

#include "core/error.hpp"

namespace thetad {

// Every call goes through the profiling names (PMPI_*), which the MPI standard guarantees: Ipopt's
// sequential MUMPS (libdmumps_seq, linked into thetad) defines stand-ins for MPI_Init,
// MPI_Comm_rank and MPI_Finalize for its own use, and the dynamic linker may bind thetad's calls to
// those (every rank then believes it is rank 0).
namespace {

enum Tag : int { kRequest = 1, kError = 2, kAnswer = 3 };

void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw Error(std::string("MPI: ") + what + " failed");
}

}  // namespace

bool MpiSession::launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr;
}

MpiSession::MpiSession() {
  int provided = 0;
  check(PMPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED) throw Error("MPI: the library does not support MPI_THREAD_FUNNELED");
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  PMPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { PMPI_Finalize(); }

std::optional<MpiSession::Request> MpiSession::poll() {
  int waiting = 0;
  MPI_Status status;
  check(PMPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status), "MPI_Iprobe");
  if (!waiting) return std::nullopt;
  int length = 0;
  PMPI_Get_count(&status, MPI_CHAR, &length);
  std::string payload(static_cast<std::size_t>(length), '\0');
  check(PMPI_Recv(payload.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Recv");
  Request request;
  request.rank = status.MPI_SOURCE;
  if (status.MPI_TAG == kError) {
    request.error = payload;
  } else if (!payload.empty()) {
    request.record = record_from_json(nlohmann::json::parse(payload));
  }
  return request;
}

void MpiSession::answer(int rank, std::optional<std::int64_t> index) {
  long long value = index ? *index : -1;
  check(PMPI_Send(&value, 1, MPI_LONG_LONG, rank, kAnswer, MPI_COMM_WORLD), "MPI_Send");
}

std::optional<std::int64_t> MpiSession::request(const std::optional<RunRecord>& finished) {
  const std::string payload = finished ? to_json(*finished).dump() : std::string();
  check(PMPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, 0, kRequest, MPI_COMM_WORLD), "MPI_Send");
  long long value = -1;
  check(PMPI_Recv(&value, 1, MPI_LONG_LONG, 0, kAnswer, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  if (value < 0) return std::nullopt;
  return static_cast<std::int64_t>(value);
}

void MpiSession::report_error(const std::string& message) {
  PMPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kError, MPI_COMM_WORLD);
}

void MpiSession::abort(int code) {
  PMPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; the compiler cannot know
}

}  // namespace thetad
