#include "voxcd/host/mpi/frame_exchange.h"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace voxcd::mpi {

namespace {

constexpr int kTagOutcomes = 0x7c01;  // a rank's outcomes for rank 0
constexpr int kTagMerged = 0x7c02;    // rank 0's merge for every rank

using Clock = std::chrono::steady_clock;

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string(what) + " failed: " + std::string(text, size_t(len)));
}

// A message with `tag` from `source` (MPI_ANY_SOURCE: any), or false when none arrives by the deadline. Polls and
// yields the processor between polls (ranks may share cores).
bool receive(int source, int tag, Clock::time_point deadline, int& from, std::string& bytes) {
  for (;;) {
    int found = 0;
    MPI_Message msg;
    MPI_Status st;
    check(MPI_Improbe(source, tag, MPI_COMM_WORLD, &found, &msg, &st), "MPI_Improbe");
    if (found) {
      int count = 0;
      MPI_Get_count(&st, MPI_CHAR, &count);
      bytes.resize(size_t(count));
      check(MPI_Mrecv(bytes.data(), count, MPI_CHAR, &msg, MPI_STATUS_IGNORE), "MPI_Mrecv");
      from = st.MPI_SOURCE;
      return true;
    }
    if (Clock::now() >= deadline) return false;
    std::this_thread::yield();
  }
}

// Sends and waits until the buffer may be reused, or returns false at the deadline (the receiver never took it).
bool send(int to, int tag, const std::string& bytes, Clock::time_point deadline) {
  MPI_Request req;
  check(MPI_Isend(bytes.data(), int(bytes.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD, &req), "MPI_Isend");
  for (;;) {
    int done = 0;
    check(MPI_Test(&req, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return true;
    if (Clock::now() >= deadline) {
      MPI_Cancel(&req);
      return false;
    }
    std::this_thread::yield();
  }
}

// VOXCD_TESTING_FRAME_FAULT=KIND:RANK:FRAME (docs/scale.md, "Testing aids"): rank RANK, at frame FRAME, fails
// (throws), exits at once, or hangs instead of exchanging.
void testing_fault(int rank, uint64_t frame) {
  const char* text = std::getenv("VOXCD_TESTING_FRAME_FAULT");
  if (!text || !*text) return;
  const std::string t = text;
  const size_t c1 = t.find(':'), c2 = c1 == std::string::npos ? c1 : t.find(':', c1 + 1);
  const std::string kind = t.substr(0, c1);
  int r = -1;
  uint64_t f = 0;
  try {
    if (c2 == std::string::npos || (kind != "fail" && kind != "hang" && kind != "exit"))
      throw std::invalid_argument("bad");
    size_t used = 0;
    r = std::stoi(t.substr(c1 + 1, c2 - c1 - 1), &used);
    if (used != c2 - c1 - 1) throw std::invalid_argument("bad");
    f = std::stoull(t.substr(c2 + 1), &used);
    if (used != t.size() - c2 - 1) throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw std::runtime_error("VOXCD_TESTING_FRAME_FAULT is '" + t + "', expected fail|hang|exit:RANK:FRAME");
  }
  if (r != rank || f != frame) return;
  if (kind == "fail") throw std::runtime_error("planted fault (VOXCD_TESTING_FRAME_FAULT=" + t + ")");
  if (kind == "exit") std::_Exit(3);
  for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

}  // namespace

MpiFrameExchange::MpiFrameExchange(World& world, double timeout) : world_(world), timeout_(timeout) {
  if (!world.distributed()) throw std::logic_error("MpiFrameExchange needs a world started by an MPI launcher");
}

std::vector<PairOutcome> MpiFrameExchange::exchange(uint64_t frame, const Slabs& slabs,
                                                    const std::vector<PairOutcome>& mine, const RankCounts& own,
                                                    RankCounts& total) {
  const int n = world_.size(), me = world_.rank();
  testing_fault(me, frame);
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(timeout_));
  std::ostringstream why;
  if (me != 0) {
    const std::string out = encode_outcomes(frame, own, mine);
    if (!send(0, kTagOutcomes, out, deadline)) {
      why << "rank " << me << " (" << slab_text(slabs, me) << "): rank 0 took no outcomes for frame " << frame
          << " within " << timeout_ << " s";
      throw std::runtime_error(why.str());
    }
    sent_ += out.size();
    int from = 0;
    std::string bytes;
    if (!receive(0, kTagMerged, deadline, from, bytes)) {
      why << "rank " << me << " (" << slab_text(slabs, me) << "): rank 0 sent no merged outcomes for frame " << frame
          << " within " << timeout_ << " s";
      throw std::runtime_error(why.str());
    }
    received_ += bytes.size();
    uint64_t f = 0;
    std::vector<PairOutcome> all;
    decode_outcomes(bytes, f, total, all);
    if (f != frame) {
      why << "rank " << me << ": rank 0 sent frame " << f << " while this rank is at frame " << frame;
      throw std::runtime_error(why.str());
    }
    return all;
  }
  std::vector<std::vector<PairOutcome>> per_rank(static_cast<size_t>(n));
  std::vector<bool> got(size_t(n), false);
  per_rank[0] = mine;
  got[0] = true;
  total = own;
  for (int k = 1; k < n; ++k) {
    int from = 0;
    std::string bytes;
    if (!receive(MPI_ANY_SOURCE, kTagOutcomes, deadline, from, bytes)) {
      why << "rank 0: no outcomes for frame " << frame << " within " << timeout_ << " s from";
      for (int r = 1; r < n; ++r)
        if (!got[size_t(r)]) why << " rank " << r << " (" << slab_text(slabs, r) << ")";
      throw std::runtime_error(why.str());
    }
    received_ += bytes.size();
    uint64_t f = 0;
    RankCounts c;
    decode_outcomes(bytes, f, c, per_rank[size_t(from)]);
    if (f != frame || got[size_t(from)]) {
      why << "rank 0: rank " << from << " (" << slab_text(slabs, from) << ") sent frame " << f << " at frame " << frame;
      throw std::runtime_error(why.str());
    }
    got[size_t(from)] = true;
    total.pairs += c.pairs;
    total.tested += c.tested;
    total.cycles = std::max(total.cycles, c.cycles);
  }
  std::vector<PairOutcome> all = merge_outcomes(per_rank);
  const std::string out = encode_outcomes(frame, total, all);
  for (int r = 1; r < n; ++r) {
    if (!send(r, kTagMerged, out, deadline)) {
      why << "rank 0: rank " << r << " (" << slab_text(slabs, r) << ") took no merged outcomes for frame " << frame
          << " within " << timeout_ << " s";
      throw std::runtime_error(why.str());
    }
    sent_ += out.size();
  }
  return all;
}

}  // namespace voxcd::mpi
