// FastRunner's scheduling of a batch (run_into): the jobs cut into pieces of points and runs of pieces (tasks) over
// the thread pool, or on the calling thread when the batch is small; each piece's records placed in the stream in
// order and every completion record timed.
#include "voxcd/ref/fast/fast.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/fast/detail/runner.h"
#include "voxcd/ref/fast/detail/records.h"
#include "voxcd/ref/fast/detail/sparse_shell.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

using detail::append_records;
using detail::kChunk;
using detail::kTaskPoints;
using detail::push_record;

uint64_t FastRunner::Impl::walk_sparse_shell(const Job& j, std::vector<detail::ShellCursor>* cursors, JobSlots* slots) const {
  const detail::ShellBricks bricks(cfg_, shell_.data() + j.shell_base, j.shell_count);
  detail::ShellWalk walk;
  detail::walk_shell(cfg_, bricks, kChunk, walk, slots);
  if (cursors) cursors->swap(walk.cursors);
  return walk.points;
}

const detail::ShellCursor* FastRunner::Impl::cursor_of(const Piece& p) const {
  return p.at == SIZE_MAX ? nullptr : piece_at_.data() + p.at;
}

size_t FastRunner::Impl::make_pieces(const std::vector<Job>& jobs) {
  // Pieces: (job, first point, end point), at most kChunk points each.
  // A sparse shell's words are walked once: its points, where each piece's begin and its slots. The jobs are not
  // validated yet: a job whose shell is not loaded is left with no points (validation refuses it before it runs).
  pieces_.clear();
  piece_at_.clear();
  first_piece_.assign(jobs.size() + 1, 0);
  batch_slots_.resize(jobs.size());
  std::vector<detail::ShellCursor> cursors;
  size_t points = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    first_piece_[j] = pieces_.size();
    const Job& job = jobs[j];
    JobSlots& slots = batch_slots_[j];
    if (!job.sparse_shell()) {  // job_slots(cfg, job), in place: a batch may hold many small jobs
      slots.lanes = uint64_t(cfg_.dense_slot_points()), slots.points = job.shell_count;
      slots.groups = job.shell_count == 0 ? 1 : (slots.points + slots.lanes - 1) / slots.lanes;
      slots.starts.clear();
    } else if (uint64_t(job.shell_base) + job.shell_count <= shell_.size()) {
      cursors.clear();
      walk_sparse_shell(job, &cursors, &slots);
    } else {
      slots = JobSlots{};
    }
    const uint32_t n = uint32_t(slots.points);
    points += n;
    for (uint32_t b = 0; b < n; b += uint32_t(kChunk)) {
      Piece& p = pieces_.emplace_back();
      p.job = j;
      p.begin = b;
      p.end = uint32_t(std::min<size_t>(n, b + kChunk));
      if (job.sparse_shell()) p.at = piece_at_.size(), piece_at_.push_back(cursors[b / kChunk]);
    }
  }
  first_piece_[jobs.size()] = pieces_.size();
  return points;
}

void FastRunner::Impl::run_serial(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate) {
  // Every job validated first, then the pieces in order, hits straight into `out`; FIRST skips the pieces after its
  // hit.
  if (validate)
    for (const Job& j : jobs) validate_job(cfg_, j, shell_.size(), map_.size());
  out.clear();
  out.reserve(2 * jobs.size());
  for (size_t j = 0; j < jobs.size(); ++j) {
    uint32_t hits = 0;
    for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
      serial_hits_.clear();
      run_chunk(jobs[j], pieces_[i].begin, pieces_[i].end, serial_hits_, hits, cursor_of(pieces_[i]));
      append_records(serial_hits_, 0, jobs[j].tag, out);
      if (jobs[j].mode == Mode::First && hits) break;
    }
    push_record(out, Record::Done, jobs[j].tag).hits = hits;
  }
  if (cycles) annotate(jobs, out);
}

void FastRunner::Impl::annotate(const std::vector<Job>& jobs, std::vector<Record>& out) const {
  // annotate_cycles with the batch's slots (a sparse shell's from make_pieces' walk of its words) and, on a banked
  // device, each job's bank cycles.
  JobSpan prev;
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t first = r;
    while (out[r].kind == Record::Hit) ++r;
    const JobHits h = job_hits(batch_slots_[j], jobs[j], j, out.data() + first, r - first, first);
    Record& done = out[r++];
    const BankCycles bank =
        cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, jobs[j], h, done.hits) : BankCycles{};
    const JobSpan span = job_span(cfg_, jobs[j], batch_slots_[j], j, h, done.hits, bank);
    done.cycles = span_cycles(cfg_, j ? &prev : nullptr, span);
    done.points = span.points;
    done.stalls = 0;
    prev = span;
  }
}

void FastRunner::Impl::run_tasks(const std::vector<Job>& jobs, bool cycles, bool validate) {
  // Tasks: runs of consecutive pieces of at least kTaskPoints points.
  task_first_.clear();
  for (size_t i = 0, acc = kTaskPoints; i < pieces_.size(); ++i) {
    if (acc >= kTaskPoints) task_first_.push_back(i), acc = 0;
    acc += pieces_[i].end - pieces_[i].begin;
  }
  task_first_.push_back(pieces_.size());
  const size_t tasks = task_first_.size() - 1;
  if (results_.size() < tasks) results_.resize(tasks);
  // Each task validates a job before its first piece of it (the task holding a job's first piece validates it
  // before any piece of a later job), and the jobs of no points before it (the first task also those before its
  // first job, the last those after its last), so the lowest task that throws, whose exception the pool rethrows,
  // names the first invalid job, as run_serial would. The lookups only read the memories, and `out` is not touched
  // before every task has finished.
  pool_->parallel_for(tasks, [&](size_t t) {
    std::vector<Record>& hits = results_[t].hits;
    HitColumns& cols = results_[t].columns;
    hits.clear();
    size_t validated = SIZE_MAX, next = t == 0 ? 0 : pieces_[task_first_[t] - 1].job + 1;
    auto check = [&](size_t j) { validate_job(cfg_, jobs[j], shell_.size(), map_.size()); };
    for (size_t i = task_first_[t]; i < task_first_[t + 1]; ++i) {
      Piece& p = pieces_[i];
      const Job& j = jobs[p.job];
      if (validate) {
        for (; next < p.job; ++next) check(next);
        if (validated != p.job) check(p.job), validated = p.job;
        next = std::max(next, p.job + 1);
      }
      p.task = t;
      p.first = hits.size();
      p.count = 0;
      cols.clear();
      run_chunk(j, p.begin, p.end, cols, p.count, cursor_of(p));
      append_records(cols, 0, j.tag, hits);
      p.records = hits.size() - p.first;
      if (cycles) p.sum = job_hits(batch_slots_[p.job], j, p.job, hits.data() + p.first, p.records);
    }
    if (validate && t + 1 == tasks)
      for (; next < jobs.size(); ++next) check(next);
  });
}

size_t FastRunner::Impl::place_records(const std::vector<Job>& jobs) {
  // Where each piece's records go: ALL every one, FIRST only those of the job's first piece with a hit; then the
  // completion record.
  size_t total = 0;
  done_at_.resize(jobs.size());
  for (size_t j = 0; j < jobs.size(); ++j) {
    bool found = false;
    for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
      Piece& p = pieces_[i];
      if (jobs[j].mode == Mode::First) {
        if (found || p.count == 0) p.records = 0;
        else found = true;
      }
      p.out = total;
      total += p.records;
    }
    done_at_[j] = total++;
  }
  return total;
}

void FastRunner::Impl::job_result(const std::vector<Job>& jobs, size_t j, bool cycles, uint32_t& hits, JobHits& sum) const {
  hits = 0;
  sum = JobHits();  // none yet: the group sentinels of job_hits
  sum.first_group = sum.last_group = batch_slots_[j].groups;
  for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
    const Piece& p = pieces_[i];
    if (jobs[j].mode == Mode::First) {
      if (p.records) hits = 1, sum = p.sum;
    } else {
      hits += p.count;
      if (cycles) sum = join_job_hits(sum, p.sum);
    }
  }
}

// Task t copies its pieces' kept records to their places and writes the completion records of the jobs from its
// first piece's to the next task's (the first task also those before, the last those after: jobs of no points have no
// pieces), with their cycles. A job's cycles need only its own span and the previous job's (ref/timing.h), so every
// task times its jobs apart; a banked device's conflict cycles of a job come from its slots' addresses (ref/banks.h).
void FastRunner::Impl::finish_task(size_t t, const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) const {
  const size_t tasks = task_first_.size() - 1;
  const std::vector<Record>& hits = results_[t].hits;
  for (size_t i = task_first_[t]; i < task_first_[t + 1]; ++i) {
    const Piece& p = pieces_[i];
    std::copy(hits.begin() + std::ptrdiff_t(p.first), hits.begin() + std::ptrdiff_t(p.first + p.records),
              out.begin() + std::ptrdiff_t(p.out));
  }
  auto conflicts = [&](const Job& job, const JobHits& sum, uint32_t n) -> BankCycles {
    return cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, job, sum, n) : BankCycles{};
  };
  const size_t j0 = t == 0 ? 0 : pieces_[task_first_[t]].job;
  const size_t j1 = t + 1 == tasks ? jobs.size() : pieces_[task_first_[t + 1]].job;
  JobSpan prev;
  for (size_t j = j0; j < j1; ++j) {
    uint32_t n = 0;
    JobHits sum;
    job_result(jobs, j, cycles, n, sum);
    Record& done = out[done_at_[j]];
    done = Record();
    done.kind = Record::Done;
    done.tag = jobs[j].tag;
    done.hits = n;
    if (!cycles) continue;
    if (j == j0 && j > 0) {
      uint32_t pn = 0;
      JobHits psum;
      job_result(jobs, j - 1, cycles, pn, psum);
      prev = job_span(cfg_, jobs[j - 1], batch_slots_[j - 1], j - 1, psum, pn, conflicts(jobs[j - 1], psum, pn));
    }
    const JobSpan span = job_span(cfg_, jobs[j], batch_slots_[j], j, sum, n, conflicts(jobs[j], sum, n));
    done.cycles = span_cycles(cfg_, j > 0 ? &prev : nullptr, span);
    done.points = span.points;
    done.stalls = 0;
    prev = span;
  }
}

void FastRunner::Impl::run_jobs(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate) {
  const size_t points = make_pieces(jobs);
  if (pieces_.size() <= 1 || !pool_ || pool_->size() <= 1 || points < kParallelMinPoints)
    return run_serial(jobs, out, cycles, validate);
  run_tasks(jobs, cycles, validate);
  const size_t total = place_records(jobs);
  // Records are trivially destructible: shrinking `out` to the total costs nothing, and growing it constructs only
  // the new ones. Every record is written by finish_task.
  out.resize(total);
  // On the pool when there is enough to share (a copy of 4,096 records takes about 5 us, a job's completion about
  // 0.1 us).
  const size_t tasks = task_first_.size() - 1;
  if (total - jobs.size() >= kParallelMinPoints || jobs.size() >= 64) {
    pool_->parallel_for(tasks, [&](size_t t) { finish_task(t, jobs, out, cycles); });
  } else {
    for (size_t t = 0; t < tasks; ++t) finish_task(t, jobs, out, cycles);
  }
}

}  // namespace voxcd
