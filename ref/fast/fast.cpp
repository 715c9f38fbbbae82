// FastRunner (fast.h): its configuration and path, its memories (load, write_shell, write_map) and the direct runs
// of jobs (run_hits, run_piece); batches are scheduled in schedule.cpp, the 2-bit kernels are two_bit.cpp's.
#include "voxcd/ref/fast/fast.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/fast/detail/runner.h"
#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/node_quads.h"
#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/sparse_shell.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

FastRunner::Impl::Impl(const DeviceConfig& cfg, unsigned threads) : cfg_(cfg) {
  cfg_.validate();
  if (cfg_.acc_width() <= 53)
    path_ = Path::Double;
  else if (cfg_.acc_width() <= 63)
    path_ = Path::Int64;
  else
    path_ = Path::Wide;
  keep_int64_ = path_ == Path::Int64 || (path_ == Path::Double && 3 * cfg_.DW >= 31);
  while ((1 << slot_bits_) < cfg_.states_per_word()) ++slot_bits_;
  tf_scale_ = std::ldexp(1.0, -cfg_.TF());
  if (threads != 1) pool_ = std::make_shared<ThreadPool>(threads);
}

FastRunner::FastRunner(const DeviceConfig& cfg, unsigned threads) : impl_(std::make_unique<Impl>(cfg, threads)) {}

FastRunner::FastRunner(const DeviceConfig& cfg, std::shared_ptr<ThreadPool> pool) : FastRunner(cfg, 1) {
  impl_->pool_ = std::move(pool);
}

FastRunner::~FastRunner() = default;

const char* FastRunner::path_name(Path p) {
  switch (p) {
    case Path::Double: return "double";
    case Path::Int64: return "int64";
    case Path::Wide: return "wide";
  }
  return "?";
}


const char* FastRunner::distance_kernel() { return detail::distance_block_name(); }

unsigned FastRunner::threads() const { return impl_->pool_ ? impl_->pool_->size() : 1; }
const DeviceConfig& FastRunner::config() const { return impl_->cfg_; }
FastRunner::Path FastRunner::path() const { return impl_->path_; }
const std::shared_ptr<ThreadPool>& FastRunner::pool() const { return impl_->pool_; }
uint64_t FastRunner::shell_words() const { return impl_->shell_.size(); }
uint64_t FastRunner::map_words() const { return impl_->map_.size(); }
const std::vector<ShellWord>& FastRunner::shell() const { return impl_->shell_; }
const std::vector<uint64_t>& FastRunner::map() const { return impl_->map_; }
uint64_t FastRunner::node_copy_limit() const { return impl_->copy_limit_; }
void FastRunner::set_node_copy_limit(uint64_t bytes) { impl_->set_node_copy_limit(bytes); }
uint64_t FastRunner::node_copy_bytes() const { return impl_->node_copy_bytes(); }
void FastRunner::load(const DeviceMemory& mem) { impl_->load(mem); }
void FastRunner::write_shell(uint64_t first, const ShellWord* words, size_t n) { impl_->write_shell(first, words, n); }
void FastRunner::write_map(uint64_t first, const uint64_t* words, size_t n) { impl_->write_map(first, words, n); }
BankCycles FastRunner::bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const {
  return impl_->bank_cycles(job, hits, done_hits);
}
uint64_t FastRunner::job_points(const Job& job) const { return impl_->job_points(job); }
JobSlots FastRunner::job_slots(const Job& job) const { return impl_->job_slots(job); }

std::vector<Record> FastRunner::run(const std::vector<Job>& jobs, bool cycles) {
  std::vector<Record> out;
  run_into(jobs, out, cycles);
  return out;
}

void FastRunner::run_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) {
  impl_->run_jobs(jobs, out, cycles, true);
}

void FastRunner::run_validated_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) {
  impl_->run_jobs(jobs, out, cycles, false);
}

void FastRunner::run_hits(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out,
                          bool cycles) const {
  impl_->run_hits(jobs, n, hits, out, cycles);
}

void FastRunner::run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                           uint32_t& count) const {
  impl_->run_piece(job, begin, end, validate, hits, count);
}

void FastRunner::Impl::set_shell_word(size_t k, const ShellWord& w) {
  shell_[k] = w;
  if (path_ == Path::Double) sx_[k] = int32_t(w.x), sy_[k] = int32_t(w.y), sz_[k] = int32_t(w.z);
  if (keep_int64_) ix_[k] = w.x, iy_[k] = w.y, iz_[k] = w.z;
}

void FastRunner::Impl::load(const DeviceMemory& mem) {
  validate_memory(cfg_, mem);
  shell_.clear();
  map_.clear();
  drop_node_quads(0, UINT64_MAX);
  write_shell(0, mem.shell.data(), mem.shell.size());
  write_map(0, mem.map.data(), mem.map.size());
}

void FastRunner::Impl::write_shell(uint64_t first, const ShellWord* words, size_t n) {
  if (first + n > cfg_.shell_depth())
    throw JobError("shell words [" + std::to_string(first) + ", " + std::to_string(first + n) +
                   ") do not fit the shell memory of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " words");
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      if (!fits_signed(words[i][c], cfg_.PW))
        throw JobError("shell word " + std::to_string(first + i) + " coordinate " + std::to_string(c) + " = " +
                       std::to_string(words[i][c]) + " does not fit PW = " + std::to_string(cfg_.PW) + " bits");
  const size_t end = size_t(first + n);
  if (shell_.size() < end) {
    shell_.resize(end);
    if (path_ == Path::Double) sx_.resize(end), sy_.resize(end), sz_.resize(end);
    if (keep_int64_) ix_.resize(end), iy_.resize(end), iz_.resize(end);
  }
  for (size_t i = 0; i < n; ++i) set_shell_word(size_t(first) + i, words[i]);
}

void FastRunner::Impl::write_map(uint64_t first, const uint64_t* words, size_t n) {
  if (first + n > cfg_.map_depth())
    throw JobError("voxmap words [" + std::to_string(first) + ", " + std::to_string(first + n) +
                   ") do not fit the voxmap memory of 2^MAW = " + std::to_string(cfg_.map_depth()) + " words");
  for (size_t i = 0; i < n; ++i)
    if (!fits_unsigned(words[i], cfg_.MEMW))
      throw JobError("voxmap word " + std::to_string(first + i) + " has bits above MEMW = " +
                     std::to_string(cfg_.MEMW));
  const size_t end = size_t(first + n);
  drop_node_quads(first, end);
  if (map_.size() < end) map_.resize(end);
  std::copy(words, words + n, map_.begin() + std::ptrdiff_t(first));
}

BankCycles FastRunner::Impl::bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const {
  return job_bank_cycles(cfg_, shell_, map_, job, hits, done_hits);
}

uint64_t FastRunner::Impl::job_points(const Job& job) const {
  return job.sparse_shell() ? walk_sparse_shell(job, nullptr, nullptr) : job.shell_count;
}

JobSlots FastRunner::Impl::job_slots(const Job& job) const {
  if (!job.sparse_shell()) return voxcd::job_slots(cfg_, job);
  JobSlots s;
  walk_sparse_shell(job, nullptr, &s);
  return s;
}

void FastRunner::Impl::run_hits(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out,
                          bool cycles) const {
  for (size_t j = 0; j < n; ++j) validate_job(cfg_, jobs[j], shell_.size(), map_.size());
  hits.clear();
  out.resize(n);
  JobSpan prev;
  JobSlots slots;
  for (size_t j = 0; j < n; ++j) {
    const Job& job = jobs[j];
    JobOutcome& o = out[j];
    o = JobOutcome();
    o.first = hits.size();
    if (job.sparse_shell()) walk_sparse_shell(job, nullptr, &slots);
    else slots = voxcd::job_slots(cfg_, job);
    run_chunk(job, 0, uint32_t(slots.points), hits, o.hits);  // FIRST stops at its hit
    o.records = hits.size() - o.first;
    if (!cycles) continue;
    // The timing model's cycles from the hits' summary, as annotate_cycles gives them for this run as a stream.
    const JobHits sum = job_hits(slots, hits.point.data() + o.first, o.records);
    o.span = job_span(cfg_, job, slots, j, sum, o.hits,
                      cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, job, sum, o.hits) : BankCycles{});
    o.cycles = span_cycles(cfg_, j ? &prev : nullptr, o.span);
    prev = o.span;
  }
}

void FastRunner::Impl::run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                           uint32_t& count) const {
  if (validate) validate_job(cfg_, job, shell_.size(), map_.size());
  run_chunk(job, begin, end, hits, count);
}

}  // namespace voxcd
