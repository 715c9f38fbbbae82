#include "voxcd/host/mpi/work_run.h"

#include <exception>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

namespace voxcd::mpi {

namespace {

// Distinct from campaign_run's tags: a message of one protocol is never taken for the other's.
enum Tag : int { kSetup = 21, kAssign = 22, kStop = 23, kResult = 24, kFailure = 25 };

using Clock = World::Clock;

// The items still to hand out, shared by rank 0's two threads.
class ItemQueue {
 public:
  ItemQueue(std::deque<uint64_t> todo, uint64_t budget) : todo_(std::move(todo)), budget_(budget) {}
  std::optional<uint64_t> next() {
    std::lock_guard<std::mutex> lock(m_);
    if (todo_.empty() || budget_ == 0) return std::nullopt;
    --budget_;
    const uint64_t s = todo_.front();
    todo_.pop_front();
    return s;
  }
  uint64_t left() {
    std::lock_guard<std::mutex> lock(m_);
    return todo_.size();
  }

 private:
  std::mutex m_;
  std::deque<uint64_t> todo_;
  uint64_t budget_;
};

// Rank 0's own items, on a thread beside the one that talks MPI.
class LocalRunner {
 public:
  LocalRunner(const RunItem& run, ItemQueue& q) : thread_([this, &run, &q] { loop(run, q); }) {}
  ~LocalRunner() {
    if (thread_.joinable()) thread_.join();
  }
  struct State {
    std::vector<std::pair<uint64_t, std::string>> results;  // finished, not yet taken
    std::optional<uint64_t> running;
    Clock::time_point since;
    std::string failure;
    bool finished = false;
  };
  State take() {
    std::lock_guard<std::mutex> lock(m_);
    State s = state_;
    state_.results.clear();
    return s;
  }

 private:
  void loop(const RunItem& run, ItemQueue& q) {
    while (auto s = q.next()) {
      {
        std::lock_guard<std::mutex> lock(m_);
        state_.running = *s;
        state_.since = Clock::now();
      }
      try {
        std::string line = run(*s);
        std::lock_guard<std::mutex> lock(m_);
        state_.results.emplace_back(*s, std::move(line));
        state_.running.reset();
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(m_);
        state_.failure = e.what();
        state_.finished = true;
        return;
      }
    }
    std::lock_guard<std::mutex> lock(m_);
    state_.finished = true;
  }
  std::mutex m_;
  State state_;
  std::thread thread_;
};

std::string seconds_text(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

// Ends every rank with an error on stderr (exit code 2).
[[noreturn]] void fault(World& w, const WorkPlan& plan, const std::string& what) {
  w.abort(2, "voxcd: error: " + what + (plan.resume_hint.empty() ? "" : " (" + plan.resume_hint + ")"));
}

}  // namespace

void release_work(World& w) {
  for (int r = 1; r < w.size(); ++r) w.send(r, kStop, "");
}

uint64_t coordinate_work(World& w, const WorkPlan& plan, const RunItem& run,
                         const std::function<void(uint64_t, const std::string&, int)>& finished) {
  ItemQueue queue(plan.todo, plan.stop_after ? plan.stop_after : UINT64_MAX);
  for (int r = 1; r < w.size(); ++r) w.send(r, kSetup, plan.setup);
  const auto timeout = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(plan.timeout));
  std::vector<std::optional<uint64_t>> busy(size_t(w.size()));
  std::vector<Clock::time_point> deadline(size_t(w.size()));
  auto assign = [&](int r) {
    if (auto s = queue.next()) {
      w.send(r, kAssign, std::to_string(*s));
      busy[size_t(r)] = *s;
      deadline[size_t(r)] = Clock::now() + timeout;
    } else {
      w.send(r, kStop, "");
      busy[size_t(r)].reset();
    }
  };
  for (int r = 1; r < w.size(); ++r) assign(r);
  LocalRunner local(run, queue);
  for (;;) {
    const LocalRunner::State mine = local.take();
    for (const auto& [item, line] : mine.results) {
      try {
        finished(item, line, 0);
      } catch (const std::exception& e) {
        fault(w, plan, "the result of rank 0 for " + plan.describe(item) + ": " + e.what());
      }
    }
    if (!mine.failure.empty())
      fault(w, plan, "rank 0 failed on " + (mine.running ? plan.describe(*mine.running) : std::string("an item")) + ": " +
            mine.failure);
    if (mine.running && Clock::now() - mine.since > timeout)
      fault(w, plan, "rank 0 did not finish " + plan.describe(*mine.running) + " within " + seconds_text(plan.timeout) +
            " (--timeout)");
    bool waiting = false;
    for (int r = 1; r < w.size(); ++r) {
      if (!busy[size_t(r)]) continue;
      waiting = true;
      if (Clock::now() > deadline[size_t(r)])
        fault(w, plan, "rank " + std::to_string(r) + " sent no result for " + plan.describe(*busy[size_t(r)]) + " within " +
              seconds_text(plan.timeout) + " (--timeout)");
    }
    if (!waiting && mine.finished) break;
    auto m = w.receive_until(Clock::now() + std::chrono::milliseconds(20));
    if (!m) continue;
    const size_t r = size_t(m->source);
    if (m->tag == kFailure)
      fault(w, plan, "rank " + std::to_string(r) + " failed on " + (busy[r] ? plan.describe(*busy[r]) : std::string("an item")) +
            ": " + m->bytes);
    if (m->tag != kResult || !busy[r])
      fault(w, plan, "rank " + std::to_string(r) + " sent an unexpected message (tag " + std::to_string(m->tag) + ")");
    const uint64_t item = *busy[r];
    try {
      finished(item, m->bytes, int(r));
    } catch (const std::exception& e) {
      fault(w, plan, "the result of rank " + std::to_string(r) + " for " + plan.describe(item) + ": " + e.what());
    }
    assign(int(r));
  }
  return queue.left();
}

void serve_work(World& w, const std::function<RunItem(const std::string& setup)>& make_runner) {
  Message first = w.receive_from(0);
  if (first.tag != kSetup) return;
  RunItem run;
  try {
    run = make_runner(first.bytes);
  } catch (const std::exception& e) {
    // Answer the first assignment with the failure, so that rank 0 names this rank.
    Message m = w.receive_from(0);
    if (m.tag == kAssign) w.send(0, kFailure, e.what());
    return;
  }
  for (;;) {
    Message m = w.receive_from(0);
    if (m.tag != kAssign) return;
    try {
      w.send(0, kResult, run(std::stoull(m.bytes)));
    } catch (const std::exception& e) {
      w.send(0, kFailure, e.what());
      return;
    }
  }
}

}  // namespace voxcd::mpi
