#include "voxcd/host/mpi/frame_exchange.h"

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace voxcd::mpi {

namespace {

constexpr int kTagOutcomes = 0x7c01;  // a rank's outcomes for rank 0
constexpr int kTagMerged = 0x7c02;    // rank 0's merge for every rank

void check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string(what) + " failed: " + std::string(text, size_t(len)));
}

// The deadline of one exchange. The exchange itself blocks in MPI (which makes progress fastest); a second thread,
// which never calls MPI, ends the process with the message of `why` when the deadline passes first. The launcher
// then ends every rank (a rank that exits with an error ends the job).
class Watchdog {
 public:
  Watchdog(double seconds, std::function<std::string()> why) : why_(std::move(why)) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    thread_ = std::thread([this, deadline] {
      std::unique_lock<std::mutex> lock(mu_);
      if (cv_.wait_until(lock, deadline, [this] { return done_; })) return;
      const std::string text = "voxcd simulate: " + why_() + "\n";
      std::fputs(text.c_str(), stderr);
      std::fflush(nullptr);
      std::_Exit(2);
    });
  }
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      done_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::function<std::string()> why_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  std::thread thread_;
};

// The next message with `tag` from `source` (MPI_ANY_SOURCE: any), whatever its size.
std::string receive(int source, int tag, int& from) {
  MPI_Message msg;
  MPI_Status st;
  check(MPI_Mprobe(source, tag, MPI_COMM_WORLD, &msg, &st), "MPI_Mprobe");
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  std::string bytes(size_t(count), '\0');
  check(MPI_Mrecv(bytes.data(), count, MPI_CHAR, &msg, MPI_STATUS_IGNORE), "MPI_Mrecv");
  from = st.MPI_SOURCE;
  return bytes;
}

void send(int to, int tag, const std::string& bytes) {
  check(MPI_Send(bytes.data(), int(bytes.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD), "MPI_Send");
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
  std::ostringstream why;
  if (me != 0) {
    const Watchdog dog(timeout_, [&] {
      std::ostringstream w;
      w << "rank " << me << " of " << n << " (" << slab_text(slabs, me) << "): no merged outcomes of frame " << frame
        << " from rank 0 within " << timeout_ << " s (--mpi-timeout)";
      return w.str();
    });
    const std::string out = encode_outcomes(frame, own, mine);
    send(0, kTagOutcomes, out);
    sent_ += out.size();
    int from = 0;
    const std::string bytes = receive(0, kTagMerged, from);
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
  std::unique_ptr<std::atomic<bool>[]> got(new std::atomic<bool>[size_t(n)]);
  for (int r = 0; r < n; ++r) got[size_t(r)] = r == 0;
  per_rank[0] = mine;
  total = own;
  {
    const Watchdog dog(timeout_, [&] {
      std::ostringstream w;
      w << "rank 0 of " << n << ": no outcomes of frame " << frame << " within " << timeout_
        << " s (--mpi-timeout) from";
      for (int r = 1; r < n; ++r)
        if (!got[size_t(r)]) w << " rank " << r << " (" << slab_text(slabs, r) << ")";
      return w.str();
    });
    for (int k = 1; k < n; ++k) {
      int from = 0;
      const std::string bytes = receive(MPI_ANY_SOURCE, kTagOutcomes, from);
      received_ += bytes.size();
      uint64_t f = 0;
      RankCounts c;
      decode_outcomes(bytes, f, c, per_rank[size_t(from)]);
      if (f != frame || got[size_t(from)]) {
        why << "rank 0: rank " << from << " (" << slab_text(slabs, from) << ") sent frame " << f << " at frame "
            << frame;
        throw std::runtime_error(why.str());
      }
      got[size_t(from)] = true;
      total.pairs += c.pairs;
      total.tested += c.tested;
      total.cycles = std::max(total.cycles, c.cycles);
    }
  }
  std::vector<PairOutcome> all = merge_outcomes(per_rank);
  const std::string out = encode_outcomes(frame, total, all);
  const Watchdog dog(timeout_, [&] {
    std::ostringstream w;
    w << "rank 0 of " << n << ": the ranks did not take the merged outcomes of frame " << frame << " within "
      << timeout_ << " s (--mpi-timeout)";
    return w.str();
  });
  for (int r = 1; r < n; ++r) {
    send(r, kTagMerged, out);
    sent_ += out.size();
  }
  return all;
}

}  // namespace voxcd::mpi
