#include "voxcd/ref/util/thread_pool.h"

#include <chrono>
#include <cstdlib>

#if defined(__linux__)
#include <sched.h>
#endif
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace voxcd {

namespace {

// The pool whose task this thread is running (a loop started from inside one runs inline).
thread_local const ThreadPool* t_inside = nullptr;

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

unsigned ThreadPool::available_cpus() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return unsigned(n);
  }
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

ThreadPool::ThreadPool(unsigned threads) {
  const unsigned cpus = available_cpus();
  if (threads == 0) threads = cpus;
  // More threads than CPUs: a spinning worker would take the CPU from the thread it waits for.
  spin_us_ = threads <= cpus ? kSpinMicros : 0;
  if (const char* env = std::getenv("VOXCD_SPIN_US")) spin_us_ = unsigned(std::strtoul(env, nullptr, 10));
  slots_ = std::make_unique<Slot[]>(threads);
  for (unsigned k = 1; k < threads; ++k) workers_.emplace_back([this, k] { worker(k); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> l(sleep_mu_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::drain(unsigned self) {
  const ThreadPool* outer = t_inside;
  t_inside = this;
  uint64_t finished = 0;
  const std::function<void(size_t)>* fn = nullptr;
  auto run_task = [&](size_t i) {
    if (!fn) fn = slots_[self].fn;  // read after a task is taken: the live loop's
    try {
      (*fn)(i);
    } catch (...) {
      std::lock_guard<std::mutex> l(error_mu_);
      if (i < error_index_) error_index_ = i, error_ = std::current_exception();
    }
    ++finished;
  };
  // Its own block from the front.
  for (;;) {
    const uint64_t w = slots_[self].range.fetch_add(uint64_t(1) << 32, std::memory_order_acq_rel);
    const size_t i = size_t(w >> 32), end = size_t(uint32_t(w));
    if (i >= end) break;
    run_task(i);
  }
  // Then the others' blocks from the back, the next thread's first.
  const unsigned threads = size();
  for (unsigned d = 1; d < threads; ++d) {
    std::atomic<uint64_t>& range = slots_[(self + d) % threads].range;
    uint64_t w = range.load(std::memory_order_acquire);
    for (;;) {
      const size_t i = size_t(w >> 32), end = size_t(uint32_t(w));
      if (i >= end) break;
      if (range.compare_exchange_weak(w, (w & ~uint64_t(0xffffffffu)) | (end - 1), std::memory_order_acq_rel,
                                      std::memory_order_acquire)) {
        run_task(end - 1);
        w = range.load(std::memory_order_acquire);
      }
    }
  }
  t_inside = outer;
  if (finished) slots_[self].finished.fetch_add(finished, std::memory_order_release);
}

void ThreadPool::worker(unsigned self) {
  Slot& slot = slots_[self];
  uint64_t seen = 0;
  for (;;) {
    // Wait for a new loop: spin first, then sleep.
    if (slot.generation.load(std::memory_order_acquire) == seen && !stop_.load(std::memory_order_acquire)) {
      bool woke = false;
      if (spin_us_) {
        // Pauses at first; then a yield between checks, so that on a busy machine the waiting worker gives its CPU
        // to whatever else wants it (the thread that will start the next loop, often).
        const auto start = std::chrono::steady_clock::now();
        const auto busy = start + std::chrono::microseconds(std::min(kBusyMicros, spin_us_));
        const auto until = start + std::chrono::microseconds(spin_us_);
        bool yielding = false;
        for (unsigned k = 1;; ++k) {
          if (slot.generation.load(std::memory_order_acquire) != seen || stop_.load(std::memory_order_relaxed)) {
            woke = true;
            break;
          }
          if (yielding) {
            std::this_thread::yield();
          } else {
            relax();
          }
          if (yielding || k % 64 == 0) {
            const auto now = std::chrono::steady_clock::now();
            if (now > until) break;
            yielding = now > busy;
          }
        }
      }
      if (!woke) {
        std::unique_lock<std::mutex> l(sleep_mu_);
        sleepers_.fetch_add(1, std::memory_order_seq_cst);
        wake_.wait(l, [&] { return slot.generation.load(std::memory_order_seq_cst) != seen || stop_.load(); });
        sleepers_.fetch_sub(1, std::memory_order_relaxed);
      }
    }
    if (stop_.load(std::memory_order_acquire)) return;
    seen = slot.generation.load(std::memory_order_acquire);
    drain(self);
  }
}

void ThreadPool::run_loop(size_t n, const std::function<void(size_t)>& fn) {
  const auto start = stats_on_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();
  error_index_ = SIZE_MAX;
  error_ = nullptr;
  const unsigned threads = size();
  ++generation_;
  // Every slot's body, then the blocks (released: a worker that takes a task from any block finds the body in its
  // own slot), then the workers' generations.
  for (unsigned k = 0; k < threads; ++k) {
    slots_[k].fn = &fn;
    slots_[k].finished_before = slots_[k].finished.load(std::memory_order_relaxed);
  }
  for (unsigned k = 0; k < threads; ++k) {
    const uint64_t b = uint64_t(n * k / threads), e = uint64_t(n * (k + 1) / threads);
    slots_[k].range.store(b << 32 | e, std::memory_order_release);
  }
  for (unsigned k = 1; k < threads; ++k) slots_[k].generation.store(generation_, std::memory_order_seq_cst);
  if (sleepers_.load(std::memory_order_seq_cst) > 0) {
    { std::lock_guard<std::mutex> l(sleep_mu_); }
    wake_.notify_all();
  }
  drain(0);
  // The tasks the workers took: the caller waits for them alone (a worker that took none is not waited for).
  auto finished = [&] {
    uint64_t f = 0;
    for (unsigned k = 0; k < threads; ++k)
      f += slots_[k].finished.load(std::memory_order_acquire) - slots_[k].finished_before;
    return f;
  };
  for (unsigned k = 1; finished() < n; ++k) k % 1024 ? relax() : std::this_thread::yield();
  if (stats_on_) {
    ++stats_.loops;
    stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (error_) std::rethrow_exception(error_);
}

void ThreadPool::parallel_for(size_t n, const std::function<void(size_t)>& fn) {
  if (n == 0) return;
  if (workers_.empty() || n == 1 || t_inside == this) {
    // Inline: the same exception as the pool would give (the lowest index's: the first to throw here).
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::lock_guard<std::mutex> call(call_mu_);
  // The count is 32 bits of the work word (less a margin for the claims past the end): longer loops in turn.
  constexpr size_t kMost = (size_t(1) << 32) - 4096;
  if (n <= kMost) return run_loop(n, fn);
  for (size_t base = 0; base < n; base += kMost) {
    const std::function<void(size_t)> part = [&](size_t i) { fn(base + i); };
    run_loop(std::min(kMost, n - base), part);
  }
}

}  // namespace voxcd
