// A fixed pool of worker threads for data-parallel loops. Results never depend on the thread count: callers
// write into per-index slots and merge in index order.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace voxcd {

class ThreadPool {
 public:
  // threads = 0: one per hardware thread. The calling thread always works too, so threads = 1 spawns none.
  explicit ThreadPool(unsigned threads = 0);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return unsigned(workers_.size()) + 1; }
  // Calls fn(i) for every i in [0, n), spread over the pool; returns when all are done. The first exception
  // thrown by fn is rethrown here after the others finish.
  void parallel_for(size_t n, const std::function<void(size_t)>& fn);

 private:
  void worker();
  void drain(const std::function<void(size_t)>* fn, size_t n);

  std::vector<std::thread> workers_;
  std::mutex mu_;
  std::condition_variable wake_, done_;
  const std::function<void(size_t)>* fn_ = nullptr;
  size_t n_ = 0;
  std::atomic<size_t> next_{0};
  size_t active_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace voxcd
