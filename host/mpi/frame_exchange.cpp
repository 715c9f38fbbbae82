#include "voxcd/host/mpi/frame_exchange.h"

#include <mpi.h>

#include <algorithm>
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

constexpr int kTagOutcomes = 0x7c02;  // a rank's outcomes for the others (plus the frame's parity)


}  // namespace

// The deadline of each exchange, held by one thread for the whole run (a thread a frame cost more than the frame's
// messages). The exchange itself blocks in MPI (which makes progress fastest); the watchdog, which never calls MPI,
// wakes every twentieth of the timeout (at most every 100 ms) and, when an armed deadline has passed, ends the
// process with the message of `why`. The launcher then ends every rank (a rank that exits with an error ends the
// job). Arming and disarming take an uncontended lock: no system call.
class Watchdog {
 public:
  explicit Watchdog(double seconds)
      : timeout_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(seconds))),
        poll_(std::clamp(timeout_ / 20, std::chrono::steady_clock::duration(std::chrono::milliseconds(1)),
                         std::chrono::steady_clock::duration(std::chrono::milliseconds(100)))) {
    thread_ = std::thread([this] { watch(); });
  }
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  // From now until disarm(), the deadline is the timeout from now; `why` says what did not arrive.
  void arm(std::function<std::string()> why) {
    std::lock_guard<std::mutex> lock(mu_);
    why_ = std::move(why);
    deadline_ = std::chrono::steady_clock::now() + timeout_;
    armed_ = true;
  }
  void disarm() {
    std::lock_guard<std::mutex> lock(mu_);
    armed_ = false;
    why_ = nullptr;
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mu_);
    while (!stop_) {
      cv_.wait_for(lock, poll_, [this] { return stop_; });
      if (stop_ || !armed_ || std::chrono::steady_clock::now() < deadline_) continue;
      const std::string text = "voxcd simulate: " + why_() + "\n";
      std::fputs(text.c_str(), stderr);
      std::fflush(nullptr);
      std::_Exit(2);
    }
  }

  const std::chrono::steady_clock::duration timeout_, poll_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::function<std::string()> why_;
  std::chrono::steady_clock::time_point deadline_;
  bool armed_ = false, stop_ = false;
  std::thread thread_;
};

namespace {

// Arms a watchdog for one scope.
class Armed {
 public:
  Armed(Watchdog& dog, std::function<std::string()> why) : dog_(dog) { dog_.arm(std::move(why)); }
  ~Armed() { dog_.disarm(); }
  Armed(const Armed&) = delete;
  Armed& operator=(const Armed&) = delete;

 private:
  Watchdog& dog_;
};

// The next message with `tag` from `source` (MPI_ANY_SOURCE: any), whatever its size.
std::string receive(int source, int tag, int& from) {
  MPI_Message msg;
  MPI_Status st;
  check_mpi(MPI_Mprobe(source, tag, MPI_COMM_WORLD, &msg, &st), "MPI_Mprobe");
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  std::string bytes(size_t(count), '\0');
  check_mpi(MPI_Mrecv(bytes.data(), count, MPI_CHAR, &msg, MPI_STATUS_IGNORE), "MPI_Mrecv");
  from = st.MPI_SOURCE;
  return bytes;
}

// The hook of the project's tests (frame_exchange.h, set_frame_fault_testing_hook); empty in the shipped tool.
FrameFaultTestingHook testing_hook = nullptr;

}  // namespace

void set_frame_fault_testing_hook(FrameFaultTestingHook hook) { testing_hook = hook; }

MpiFrameExchange::MpiFrameExchange(World& world, double timeout) : world_(world), timeout_(timeout) {
  if (!world.distributed()) throw std::logic_error("MpiFrameExchange needs a world started by an MPI launcher");
  dog_ = std::make_unique<Watchdog>(timeout);
}

MpiFrameExchange::~MpiFrameExchange() = default;

std::vector<PairOutcome> MpiFrameExchange::exchange(uint64_t frame, const Slabs& slabs,
                                                    const std::vector<PairOutcome>& mine, const RankCounts& own,
                                                    RankCounts& total) {
  const int n = world_.size(), me = world_.rank();
  if (testing_hook) testing_hook(me, frame);
  // Every rank sends its outcomes to every other and merges what it receives (all ranks at once: no rank waits
  // for another's merge). A rank is at most one frame ahead of any other (it needs their outcomes of its frame to
  // go on), so the frame's parity in the tag keeps two frames' messages apart.
  const int tag = kTagOutcomes + int(frame & 1);
  const std::string out = encode_outcomes(frame, own, mine);
  std::vector<MPI_Request> sends;
  sends.reserve(size_t(n));
  for (int r = 0; r < n; ++r) {
    if (r == me) continue;
    sends.emplace_back();
    check_mpi(MPI_Isend(out.data(), int(out.size()), MPI_CHAR, r, tag, MPI_COMM_WORLD, &sends.back()), "MPI_Isend");
    sent_ += out.size();
  }
  std::vector<std::vector<PairOutcome>> per_rank(static_cast<size_t>(n));
  std::vector<char> got(size_t(n), 0);
  got[size_t(me)] = 1;
  per_rank[size_t(me)] = mine;
  total = own;
  {
    const Armed armed(*dog_, [&] {
      std::ostringstream w;
      w << "rank " << me << " of " << n << ": ";
      if (std::count(got.begin(), got.end(), 1) == n) {
        w << "the other ranks did not take the outcomes of frame " << frame << " within " << timeout_
          << " s (--mpi-timeout)";
        return w.str();
      }
      w << "no outcomes of frame " << frame << " within " << timeout_ << " s (--mpi-timeout) from";
      for (int r = 0; r < n; ++r)
        if (!got[size_t(r)]) w << " rank " << r << " (" << slab_text(slabs, r) << ")";
      return w.str();
    });
    for (int k = 1; k < n; ++k) {
      int from = 0;
      const std::string bytes = receive(MPI_ANY_SOURCE, tag, from);
      received_ += bytes.size();
      uint64_t f = 0;
      RankCounts c;
      decode_outcomes(bytes, f, c, per_rank[size_t(from)]);
      if (f != frame || got[size_t(from)]) {
        std::ostringstream why;
        why << "rank " << me << ": rank " << from << " (" << slab_text(slabs, from) << ") sent frame " << f
            << " at frame " << frame;
        throw std::runtime_error(why.str());
      }
      got[size_t(from)] = 1;
      total.pairs += c.pairs;
      total.tested += c.tested;
      total.cycles = std::max(total.cycles, c.cycles);
    }
    // Every rank has sent this frame's outcomes too, so this completes at once.
    check_mpi(MPI_Waitall(int(sends.size()), sends.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  }
  return merge_outcomes(per_rank);
}

}  // namespace voxcd::mpi
