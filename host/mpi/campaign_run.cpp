// A campaign's shards as work items of work_run.h: the setup is the campaign, an item's result its result line.
#include "voxcd/host/mpi/campaign_run.h"

#include <chrono>
#include <deque>
#include <memory>
#include <stdexcept>

#include "voxcd/host/mpi/work_run.h"
#include "voxcd/host/regress/results_file.h"
#include "voxcd/host/regress/shard.h"

namespace voxcd::mpi {

namespace {

std::string shard_text(const Campaign& c, uint64_t s) {
  return "shard " + std::to_string(s) + " (" + describe(shard_at(c, s)) + ")";
}

// Runs shards of c on this rank, keeping the last vectors it generated for the next shard.
RunItem shard_runner(const Campaign& c, const ShardOptions& opt, int rank) {
  auto cache = std::make_shared<ShardVectors>();
  return [&c, cache, opt, rank](uint64_t s) {
    ShardResult r = run_shard(c, shard_at(c, s), *cache, opt);
    r.rank = rank;
    return shard_result_line(r, shard_at(c, s));
  };
}

// The shards the report does not hold yet, and how the run names them.
WorkPlan campaign_plan(const Campaign& c, const Report& report, const RunOptions& opt) {
  WorkPlan plan;
  plan.setup = campaign_json(c);
  for (uint64_t s = 0; s < c.shards(); ++s)
    if (!report.has(s)) plan.todo.push_back(s);
  plan.describe = [&c](uint64_t s) { return shard_text(c, s); };
  plan.resume_hint = "every shard finished before is in the results file; rerun with it to resume";
  plan.unknown = "a shard";
  plan.timeout = opt.timeout;
  plan.stop_after = opt.stop_after;
  return plan;
}

}  // namespace

void release_workers(World& w) { release_work(w); }

Report coordinate(World& w, const Campaign& c, const RunOptions& opt) {
  const auto start = World::Clock::now();
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
  const WorkPlan plan = campaign_plan(c, report, opt);
  coordinate_work(w, plan, shard_runner(c, opt.shard(), 0), [&](uint64_t item, const std::string& line, int rank) {
    const ShardResult r = parse_shard_result(line, c, "the result of rank " + std::to_string(rank));
    if (r.shard != item) throw std::runtime_error("it is the result of shard " + std::to_string(r.shard));
    if (results) results->append(r, shard_at(c, r.shard));
    report.add(r, false);
  });
  if (!report.complete())
    report.stopped = "--stop-after " + std::to_string(opt.stop_after) + " ended this run; rerun with the same " +
                     "--results file to run the other shards";
  report.seconds = std::chrono::duration<double>(World::Clock::now() - start).count();
  report.bytes_between_ranks = w.bytes_sent() + w.bytes_received();
  return report;
}

void serve(World& w, const ShardOptions& opt) {
  std::unique_ptr<Campaign> c;
  serve_work(w, [&](const std::string& setup) {
    c = std::make_unique<Campaign>(campaign_from_json(setup, "the campaign from rank 0"));
    return shard_runner(*c, opt, w.rank());
  });
}

}  // namespace voxcd::mpi
