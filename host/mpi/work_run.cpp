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

namespace {

// Rank 0's side of a run: which item each other rank holds and until when, its own runner's results, the faults.
class Coordinator {
 public:
  Coordinator(World& w, const WorkPlan& plan, const std::function<void(uint64_t, const std::string&, int)>& finished)
      : w_(w), plan_(plan), finished_(finished), queue_(plan.todo, plan.stop_after ? plan.stop_after : UINT64_MAX),
        timeout_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(plan.timeout))),
        busy_(size_t(w.size())), deadline_(size_t(w.size())) {}

  uint64_t run(const RunItem& run) {
    for (int r = 1; r < w_.size(); ++r) w_.send(r, kSetup, plan_.setup);
    for (int r = 1; r < w_.size(); ++r) assign(r);
    LocalRunner local(run, queue_);
    for (;;) {
      const bool mine_finished = take_local(local.take());
      if (!check_deadlines() && mine_finished) break;
      if (auto m = w_.receive_until(Clock::now() + std::chrono::milliseconds(20))) take_message(*m);
    }
    return queue_.left();
  }

 private:
  // Hands rank r its next item, or tells it to stop.
  void assign(int r) {
    if (auto s = queue_.next()) {
      w_.send(r, kAssign, std::to_string(*s));
      busy_[size_t(r)] = *s;
      deadline_[size_t(r)] = Clock::now() + timeout_;
    } else {
      w_.send(r, kStop, "");
      busy_[size_t(r)].reset();
    }
  }

  void deliver(uint64_t item, const std::string& line, int rank) {
    try {
      finished_(item, line, rank);
    } catch (const std::exception& e) {
      fault(w_, plan_, "the result of rank " + std::to_string(rank) + " for " + plan_.describe(item) + ": " + e.what());
    }
  }

  // Rank 0's own results and faults; true when its runner has finished.
  bool take_local(const LocalRunner::State& mine) {
    for (const auto& [item, line] : mine.results) deliver(item, line, 0);
    if (!mine.failure.empty())
      fault(w_, plan_, "rank 0 failed on " + (mine.running ? plan_.describe(*mine.running) : plan_.unknown) + ": " +
            mine.failure);
    if (mine.running && Clock::now() - mine.since > timeout_)
      fault(w_, plan_, "rank 0 did not finish " + plan_.describe(*mine.running) + " within " +
            seconds_text(plan_.timeout) + " (--timeout)");
    return mine.finished;
  }

  // True while another rank holds an item; a fault when one has held it past its deadline.
  bool check_deadlines() {
    bool waiting = false;
    for (int r = 1; r < w_.size(); ++r) {
      if (!busy_[size_t(r)]) continue;
      waiting = true;
      if (Clock::now() > deadline_[size_t(r)])
        fault(w_, plan_, "rank " + std::to_string(r) + " sent no result for " + plan_.describe(*busy_[size_t(r)]) +
              " within " + seconds_text(plan_.timeout) + " (--timeout)");
    }
    return waiting;
  }

  void take_message(const Message& m) {
    const size_t r = size_t(m.source);
    if (m.tag == kFailure)
      fault(w_, plan_, "rank " + std::to_string(r) + " failed on " +
            (busy_[r] ? plan_.describe(*busy_[r]) : plan_.unknown) + ": " + m.bytes);
    if (m.tag != kResult || !busy_[r])
      fault(w_, plan_, "rank " + std::to_string(r) + " sent an unexpected message (tag " + std::to_string(m.tag) + ")");
    deliver(*busy_[r], m.bytes, int(r));
    assign(int(r));
  }

  World& w_;
  const WorkPlan& plan_;
  const std::function<void(uint64_t, const std::string&, int)>& finished_;
  ItemQueue queue_;
  Clock::duration timeout_;
  std::vector<std::optional<uint64_t>> busy_;  // each other rank's item
  std::vector<Clock::time_point> deadline_;    // and its deadline
};

}  // namespace

uint64_t coordinate_work(World& w, const WorkPlan& plan, const RunItem& run,
                         const std::function<void(uint64_t, const std::string&, int)>& finished) {
  return Coordinator(w, plan, finished).run(run);
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
