// A fixed pool of worker threads for data-parallel loops. Results never depend on the thread count: callers
// write into per-index slots and merge in index order.
//
// Made for loops of a few microseconds (a frame of `voxcd simulate` runs about ten of them): after a loop its
// workers wait for the next one spinning for up to kSpinMicros before they sleep, so a loop started within that
// time costs a few cache lines and no system call (a sleeping worker costs a futex wake-up, tens of microseconds on
// a virtual machine). A pool with more threads than the CPUs the process may run on never spins.
//
// Thread k of T (the caller is thread 0) takes the indices of the k-th of T equal blocks of a loop first, in order,
// and then takes the others' last indices while any are left: loops over the same ranges find their data where
// they left it (a cache line moves between the cores of this machine in about 200 ns), and a thread that is late
// or slow has its work taken by the others. docs/scale.md, "Every core in a process".
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace voxcd {

class ThreadPool {
 public:
  // threads = 0: one per CPU the process may run on (its affinity mask: all hardware threads, or those taskset
  // allows). The calling thread always works too, so threads = 1 spawns none.
  explicit ThreadPool(unsigned threads = 0);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return unsigned(workers_.size()) + 1; }
  // Calls fn(i) for every i in [0, n), spread over the pool (tasks claimed one at a time, in index order); returns
  // when all are done. When fn throws, the exception of the lowest index is rethrown here after the others finish
  // (the same one whatever the thread count). Called from inside a task of this pool (a nested loop), it runs the
  // loop on the calling thread. Loops from several outside threads at once run one after another.
  void parallel_for(size_t n, const std::function<void(size_t)>& fn);

  // Loops run on the workers (not those run inline) and the calling thread's wall time in them, counted from
  // enable_stats(true) on (off by default: it reads the clock twice a loop). For measuring how much of a program's
  // time its loops take (bench_threads).
  struct Stats {
    uint64_t loops = 0;
    double seconds = 0;
  };
  void enable_stats(bool on) { stats_on_ = on; }
  Stats stats() const { return stats_; }
  void reset_stats() { stats_ = Stats(); }

  // The CPUs this process may run on (sched_getaffinity; hardware_concurrency where that fails), at least 1.
  static unsigned available_cpus();
  // How long an idle worker spins for the next loop before it sleeps (the environment variable VOXCD_SPIN_US, read
  // when a pool is made, overrides it; 0: sleep at once), and for how much of that it spins without yielding.
  static constexpr unsigned kSpinMicros = 1000, kBusyMicros = 50;

 private:
  void worker(unsigned self);
  void drain(unsigned self);
  void run_loop(size_t n, const std::function<void(size_t)>& fn);

  std::vector<std::thread> workers_;
  unsigned spin_us_ = kSpinMicros;  // 0: no spinning
  bool stats_on_ = false;
  Stats stats_;
  std::mutex call_mu_;  // one loop at a time
  // Per thread, on a cache line of its own, what it needs of a loop (one line moves to start it): the loop's
  // generation and body, written by the caller; its block, in one word: the next index to take from the front (high
  // half) and one past the last index left (low half); and on the next line the tasks it has finished, counted over
  // every loop. The owner takes from the front with a fetch_add,
  // the others from the back with a compare-and-swap. A thread that takes an index below the end it read has a task
  // of the live loop (a loop ends only when all its tasks are done), whose body it then reads; between loops every
  // block is empty, so a late worker takes nothing.
  struct alignas(64) Slot {
    std::atomic<uint64_t> generation{0};
    const std::function<void(size_t)>* fn = nullptr;
    std::atomic<uint64_t> range{0};
    // On a line of its own: the caller polls it while the owner still takes tasks from `range`.
    alignas(64) std::atomic<uint64_t> finished{0};
    uint64_t finished_before = 0;  // the caller's copy of `finished` when the loop started
  };
  std::unique_ptr<Slot[]> slots_;
  uint64_t generation_ = 0;  // the caller's
  std::mutex error_mu_;
  size_t error_index_ = SIZE_MAX;  // the lowest index that threw, and its exception
  std::exception_ptr error_;
  // Workers asleep.
  alignas(64) std::atomic<unsigned> sleepers_{0};
  std::mutex sleep_mu_;
  std::condition_variable wake_;
  std::atomic<bool> stop_{false};
};

// [0, n) cut into `parts` contiguous ranges of near-equal size, the first n % parts one longer: part p is
// [begin(p), end(p)). For loops whose items are too small to be tasks of their own.
struct Ranges {
  size_t n = 0, parts = 0;
  Ranges(size_t n_, size_t parts_) : n(n_), parts(std::max<size_t>(1, std::min(parts_, n_))) {}
  // At most `per_thread` parts per thread of `threads`, each of at least `grain` items (one part when n <= grain).
  static Ranges of(size_t n, size_t grain, unsigned threads, size_t per_thread = 4) {
    const size_t by_grain = grain ? (n + grain - 1) / grain : n;
    return Ranges(n, std::min(by_grain, size_t(threads) * per_thread));
  }
  size_t begin(size_t p) const { return p * (n / parts) + std::min(p, n % parts); }
  size_t end(size_t p) const { return begin(p + 1); }
};

// Ranges of [0, n) for `pool` (Ranges::of over its threads; one range without a pool).
inline Ranges pool_ranges(const ThreadPool* pool, size_t n, size_t grain, size_t per_thread = 4) {
  return pool && pool->size() > 1 ? Ranges::of(n, grain, pool->size(), per_thread) : Ranges(n, 1);
}

// fn(part, begin, end) for every part of r: on the pool, or in turn on the calling thread without one (or with one
// part).
template <class Fn>
void for_ranges(ThreadPool* pool, const Ranges& r, Fn&& fn) {
  if (r.n == 0) return;
  if (!pool || r.parts <= 1) {
    for (size_t p = 0; p < r.parts; ++p) fn(p, r.begin(p), r.end(p));
    return;
  }
  pool->parallel_for(r.parts, [&](size_t p) { fn(p, r.begin(p), r.end(p)); });
}

// A slot of per-part results on a cache line of its own (no false sharing between the threads that fill them).
template <class T>
struct alignas(64) PartSlot {
  T value{};
};

}  // namespace voxcd
