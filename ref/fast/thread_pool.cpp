#include "voxcd/ref/fast/thread_pool.h"

#include <chrono>

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
  spin_ = threads <= cpus;
  for (unsigned k = 1; k < threads; ++k) workers_.emplace_back([this] { worker(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> l(sleep_mu_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::drain(Loop& loop) {
  const ThreadPool* outer = t_inside;
  t_inside = this;
  size_t finished = 0;
  for (size_t i; (i = loop.next.fetch_add(1, std::memory_order_relaxed)) < loop.n;) {
    try {
      (*loop.fn)(i);
    } catch (...) {
      std::lock_guard<std::mutex> l(loop.error_mu);
      if (i < loop.error_index) loop.error_index = i, loop.error = std::current_exception();
    }
    ++finished;
  }
  t_inside = outer;
  if (finished) loop.done.fetch_add(finished, std::memory_order_acq_rel);
}

void ThreadPool::worker() {
  uint64_t seen = 0;
  for (;;) {
    // Wait for a new generation: spin first, then sleep.
    if (generation_.load(std::memory_order_acquire) == seen && !stop_.load(std::memory_order_acquire)) {
      bool woke = false;
      if (spin_) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicros);
        for (unsigned k = 1;; ++k) {
          if (generation_.load(std::memory_order_acquire) != seen || stop_.load(std::memory_order_relaxed)) {
            woke = true;
            break;
          }
          relax();
          if (k % 64 == 0 && std::chrono::steady_clock::now() > until) break;
        }
      }
      if (!woke) {
        std::unique_lock<std::mutex> l(sleep_mu_);
        sleepers_.fetch_add(1, std::memory_order_seq_cst);
        wake_.wait(l, [&] { return generation_.load(std::memory_order_seq_cst) != seen || stop_.load(); });
        sleepers_.fetch_sub(1, std::memory_order_relaxed);
      }
    }
    if (stop_.load(std::memory_order_acquire)) return;
    seen = generation_.load(std::memory_order_acquire);
    // Announce, then read the loop (null when its caller has closed it already).
    users_.fetch_add(1, std::memory_order_seq_cst);
    if (Loop* loop = loop_.load(std::memory_order_seq_cst)) drain(*loop);
    users_.fetch_sub(1, std::memory_order_release);
  }
}

void ThreadPool::parallel_for(size_t n, const std::function<void(size_t)>& fn) {
  if (n == 0) return;
  if (workers_.empty() || n == 1 || t_inside == this) {
    // Inline: the same exception as the pool would give (the lowest index's: the first to throw here).
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::lock_guard<std::mutex> call(call_mu_);
  const auto start = stats_on_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();
  Loop loop;
  loop.fn = &fn;
  loop.n = n;
  loop_.store(&loop, std::memory_order_seq_cst);
  generation_.fetch_add(1, std::memory_order_seq_cst);
  if (sleepers_.load(std::memory_order_seq_cst) > 0) {
    { std::lock_guard<std::mutex> l(sleep_mu_); }
    wake_.notify_all();
  }
  drain(loop);
  // Wait for the tasks the workers claimed, then close the loop and wait for every worker that may still read it.
  for (unsigned k = 1; loop.done.load(std::memory_order_acquire) < n; ++k) k % 1024 ? relax() : std::this_thread::yield();
  loop_.store(nullptr, std::memory_order_seq_cst);
  for (unsigned k = 1; users_.load(std::memory_order_seq_cst) != 0; ++k) k % 1024 ? relax() : std::this_thread::yield();
  if (stats_on_) {
    ++stats_.loops;
    stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (loop.error) std::rethrow_exception(loop.error);
}

}  // namespace voxcd
