#include "voxcd/host/mpi/campaign_run.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "voxcd/host/regress/results_file.h"
#include "voxcd/host/regress/shard.h"

namespace voxcd::mpi {

namespace {

enum Tag : int { kCampaign = 1, kAssign = 2, kStop = 3, kResult = 4, kFailure = 5 };

using Clock = World::Clock;

// The shards still to run, shared by rank 0's two threads.
class ShardQueue {
 public:
  ShardQueue(std::deque<uint64_t> todo, uint64_t budget) : todo_(std::move(todo)), budget_(budget) {}
  // The next shard, or nothing when none is left or the budget is spent.
  std::optional<uint64_t> next() {
    std::lock_guard<std::mutex> lock(m_);
    if (todo_.empty() || budget_ == 0) return std::nullopt;
    --budget_;
    const uint64_t s = todo_.front();
    todo_.pop_front();
    return s;
  }
  bool stopped_early() {
    std::lock_guard<std::mutex> lock(m_);
    return !todo_.empty();
  }

 private:
  std::mutex m_;
  std::deque<uint64_t> todo_;
  uint64_t budget_;
};

// Rank 0's own shards, on a thread beside the one that talks MPI.
class LocalRunner {
 public:
  LocalRunner(const Campaign& c, ShardQueue& q, unsigned threads)
      : thread_([this, &c, &q, threads] { loop(c, q, threads); }) {}
  ~LocalRunner() {
    if (thread_.joinable()) thread_.join();
  }
  struct State {
    std::vector<ShardResult> results;  // finished, not yet taken
    std::optional<uint64_t> running;   // the shard it runs and since when
    Clock::time_point since;
    std::string failure;               // what ended it early
    bool finished = false;
  };
  // Takes what it finished so far, and where it is.
  State take() {
    std::lock_guard<std::mutex> lock(m_);
    State s = state_;
    state_.results.clear();
    return s;
  }

 private:
  void loop(const Campaign& c, ShardQueue& q, unsigned threads) {
    ShardVectors cache;
    while (auto s = q.next()) {
      {
        std::lock_guard<std::mutex> lock(m_);
        state_.running = *s;
        state_.since = Clock::now();
      }
      try {
        ShardResult r = run_shard(c, shard_at(c, *s), cache, threads);
        std::lock_guard<std::mutex> lock(m_);
        state_.results.push_back(std::move(r));
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

[[noreturn]] void fault(World& w, const std::string& what) {
  w.abort(2, "voxcd: error: " + what +
                 " (every shard finished before is in the results file; rerun with it to resume)");
}

std::string seconds_text(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

std::string shard_text(const Campaign& c, uint64_t s) {
  return "shard " + std::to_string(s) + " (" + describe(shard_at(c, s)) + ")";
}

}  // namespace

void release_workers(World& w) {
  for (int r = 1; r < w.size(); ++r) w.send(r, kStop, "");
}

Report coordinate(World& w, const Campaign& c, const RunOptions& opt) {
  const auto start = Clock::now();
  Report report(c);
  report.ranks = w.size();
  std::unique_ptr<ResultsFile> results;
  try {
    if (!opt.results.empty()) results = std::make_unique<ResultsFile>(opt.results, c);
  } catch (...) {
    release_workers(w);
    throw;
  }
  if (results)
    for (const ShardResult& r : results->finished()) report.add(r, true);
  std::deque<uint64_t> todo;
  for (uint64_t s = 0; s < c.shards(); ++s)
    if (!report.has(s)) todo.push_back(s);
  ShardQueue queue(std::move(todo), opt.stop_after ? opt.stop_after : UINT64_MAX);
  const std::string campaign = campaign_json(c);
  for (int r = 1; r < w.size(); ++r) w.send(r, kCampaign, campaign);

  const auto timeout = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(opt.timeout));
  auto finish = [&](const ShardResult& r) {
    if (results) results->append(r, shard_at(c, r.shard));
    report.add(r, false);
  };
  // Each other rank's shard and its deadline.
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
  LocalRunner local(c, queue, opt.threads);
  for (;;) {
    const LocalRunner::State mine = local.take();
    for (const ShardResult& r : mine.results) finish(r);
    if (!mine.failure.empty())
      fault(w, "rank 0 failed on " + (mine.running ? shard_text(c, *mine.running) : std::string("a shard")) + ": " +
                   mine.failure);
    if (mine.running && Clock::now() - mine.since > timeout)
      fault(w, "rank 0 did not finish " + shard_text(c, *mine.running) + " within " + seconds_text(opt.timeout) +
                   " (--timeout)");
    bool waiting = false;
    for (int r = 1; r < w.size(); ++r) {
      if (!busy[size_t(r)]) continue;
      waiting = true;
      if (Clock::now() > deadline[size_t(r)])
        fault(w, "rank " + std::to_string(r) + " sent no result for " + shard_text(c, *busy[size_t(r)]) + " within " +
                     seconds_text(opt.timeout) + " (--timeout)");
    }
    if (!waiting && mine.finished) break;
    auto m = w.receive_until(Clock::now() + std::chrono::milliseconds(20));
    if (!m) continue;
    const size_t r = size_t(m->source);
    if (m->tag == kFailure)
      fault(w, "rank " + std::to_string(r) + " failed on " +
                   (busy[r] ? shard_text(c, *busy[r]) : std::string("a shard")) + ": " + m->bytes);
    if (m->tag != kResult || !busy[r])
      fault(w, "rank " + std::to_string(r) + " sent an unexpected message (tag " + std::to_string(m->tag) + ")");
    ShardResult res = parse_shard_result(m->bytes, c, "the result of rank " + std::to_string(r));
    if (res.shard != *busy[r])
      fault(w, "rank " + std::to_string(r) + " sent the result of shard " + std::to_string(res.shard) +
                   " for " + shard_text(c, *busy[r]));
    finish(res);
    assign(int(r));
  }
  if (!report.complete())
    report.stopped = "--stop-after " + std::to_string(opt.stop_after) + " ended this run; rerun with the same " +
                     "--results file to run the other shards";
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.bytes_between_ranks = w.bytes_sent() + w.bytes_received();
  return report;
}

void serve(World& w, unsigned threads) {
  Message first = w.receive_from(0);
  if (first.tag != kCampaign) return;
  const Campaign c = campaign_from_json(first.bytes, "the campaign from rank 0");
  ShardVectors cache;
  for (;;) {
    Message m = w.receive_from(0);
    if (m.tag != kAssign) return;
    const uint64_t s = std::stoull(m.bytes);
    try {
      ShardResult r = run_shard(c, shard_at(c, s), cache, threads);
      r.rank = w.rank();
      w.send(0, kResult, shard_result_line(r, shard_at(c, s)));
    } catch (const std::exception& e) {
      w.send(0, kFailure, e.what());
      return;
    }
  }
}

}  // namespace voxcd::mpi
