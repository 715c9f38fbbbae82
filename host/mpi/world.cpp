#include "voxcd/host/mpi/world.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace voxcd::mpi {

namespace {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

// Receives the message `msg` that MPI_Improbe/MPI_Mprobe matched.
Message receive_matched(MPI_Message& msg, const MPI_Status& st) {
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  Message m;
  m.source = st.MPI_SOURCE;
  m.tag = st.MPI_TAG;
  m.bytes.resize(size_t(count));
  check_mpi(MPI_Mrecv(m.bytes.data(), count, MPI_CHAR, &msg, MPI_STATUS_IGNORE), "MPI_Mrecv");
  return m;
}

}  // namespace

void check_mpi(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string(what) + " failed: " + std::string(text, size_t(len)));
}

World::World() {
  if (!launched_by_mpi()) return;
  int provided = 0;
  check_mpi(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  mpi_ = true;
  // Errors come back as codes (and become exceptions here) instead of ending the job unexplained.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

World::~World() {
  if (mpi_) MPI_Finalize();
}

void World::send(int to, int tag, const std::string& bytes) {
  if (!mpi_) throw std::logic_error("World::send without MPI");
  check_mpi(MPI_Send(bytes.data(), int(bytes.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD), "MPI_Send");
  sent_ += bytes.size();
}

std::optional<Message> World::receive_until(Clock::time_point deadline) {
  for (;;) {
    if (mpi_) {
      int found = 0;
      MPI_Message msg;
      MPI_Status st;
      check_mpi(MPI_Improbe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &found, &msg, &st), "MPI_Improbe");
      if (found) {
        Message m = receive_matched(msg, st);
        received_ += m.bytes.size();
        return m;
      }
    }
    if (Clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

Message World::receive_from(int from) {
  if (!mpi_) throw std::logic_error("World::receive_from without MPI");
  MPI_Message msg;
  MPI_Status st;
  check_mpi(MPI_Mprobe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &msg, &st), "MPI_Mprobe");
  Message m = receive_matched(msg, st);
  received_ += m.bytes.size();
  return m;
}

void World::abort(int code, const std::string& message) {
  std::cout.flush();
  std::cerr.flush();
  const std::string line = message + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(nullptr);
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

}  // namespace voxcd::mpi
