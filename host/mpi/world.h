// The processes of a run and the messages between them: Open MPI's C API behind a small class, started only by the
// commands that need it (voxcd regress) and only when an MPI launcher (mpirun, srun) started the process.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace voxcd::mpi {

// Throws std::runtime_error "<what> failed: <MPI's error text>" unless rc is MPI_SUCCESS (rc: an MPI call's result).
void check_mpi(int rc, const char* what);

struct Message {
  int source = 0;
  int tag = 0;
  std::string bytes;
};

class World {
 public:
  using Clock = std::chrono::steady_clock;

  // Initialises MPI (one thread calls it, others may run beside) when the environment shows an MPI launcher
  // (OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK set); otherwise a world of one rank that never calls MPI.
  World();
  // Finalises MPI when it was initialised.
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool distributed() const { return mpi_; }

  // Sends `bytes` to rank `to` with `tag` (returns when the buffer may be reused).
  void send(int to, int tag, const std::string& bytes);
  // The next message from any rank, or nothing if none has arrived by `deadline` (polls; never blocks longer).
  std::optional<Message> receive_until(Clock::time_point deadline);
  // The next message from rank `from`, waiting as long as it takes (for ranks that only answer rank 0).
  Message receive_from(int from);
  // Ends every rank of the run with `code` (MPI_Abort), or this process when there is no MPI.
  // Writes `message` and a newline to stderr in one write (so that the launcher's own report of the abort cannot
  // split it), then ends every rank with `code`.
  [[noreturn]] void abort(int code, const std::string& message);

  uint64_t bytes_sent() const { return sent_; }
  uint64_t bytes_received() const { return received_; }

 private:
  bool mpi_ = false;
  int rank_ = 0, size_ = 1;
  uint64_t sent_ = 0, received_ = 0;
};

}  // namespace voxcd::mpi
