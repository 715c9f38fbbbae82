#include "voxcd/sysc/tlm_target.h"

#include <algorithm>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/timing.h"

namespace voxcd::sysc {

using namespace sc_core;

TlmTarget::TlmTarget(sc_module_name name, const DeviceConfig& cfg, sc_time clock_period, sc_time access_latency,
                     unsigned threads)
    : DeviceTarget(name, cfg, clock_period, access_latency), runner_(cfg, threads) {}

sc_time TlmTarget::start(sc_time& delay) { return sc_time_stamp() + delay; }

// The write port takes one word per cycle from the first edge after t at which the device is idle.
sc_time TlmTarget::memory_write(uint64_t words, sc_time t) {
  const uint64_t first = std::max(edge_after(t), idle_);
  return edge_time(first + words);
}

sc_time TlmTarget::write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_time t) {
  runner_.write_shell(first, words.data(), words.size());
  return memory_write(words.size(), t);
}

sc_time TlmTarget::write_map(uint64_t first, const std::vector<uint64_t>& words, sc_time t) {
  runner_.write_map(first, words.data(), words.size());
  return memory_write(words.size(), t);
}

void TlmTarget::launch(std::vector<Job>& jobs, sc_time t) {
  // Memory writes wait for every launched batch, so the memory seen now is the memory the batch reads. Every job
  // was validated when it was staged, and the loaded memories only grow: no need to check again.
  // The completion records get ref/timing.h's cycles as annotate_cycles gives them (cycles, points, no stalls): from
  // the runner, or on a banked device from the bank cycles, which the conflict counter needs too. A sparse shell's
  // slots follow its words (the shell memory).
  const bool banked = cfg_.banked();
  runner_.run_validated_into(jobs, batch_, /*cycles=*/!banked);
  std::vector<BankCycles> bank(jobs.size());
  if (banked) {
    bank = bank_cycles(cfg_, runner_.shell(), runner_.map(), jobs, batch_);
    annotate_cycles(cfg_, runner_.shell(), jobs, batch_, bank);
  }
  future_.erase(future_.begin(), future_.begin() + std::ptrdiff_t(future_head_));  // the jobs already readable
  future_head_ = 0;
  uint8_t* out = queue_records(batch_.size());
  // The first job is presented at the start edge and accepted at the next; a completion record emitted `cycles`
  // after the previous one (the first: after acceptance) is taken one edge after its emission.
  const uint64_t start_edge = std::max(edge_after(t), batch_free_);
  uint64_t edge = start_edge + 2;
  size_t r = 0, last_first = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    last_first = r;
    for (; batch_[r].kind == Record::Hit; ++r) encode_record(batch_[r], out + r * kRecordBytes);
    const Record& done = batch_[r];
    encode_record(done, out + r * kRecordBytes);
    ++r;
    edge += *done.cycles;
    future_.push_back({edge, r - last_first, {done.hits, *done.points, *done.cycles, 0, bank[j].conflicts}});
  }
  batch_free_ = edge;
  // The device is idle one edge after the last completion record is taken, or later when slots issued behind a
  // FIRST job's hit still hold the pipeline: they leave the hit-test stage one per edge, from the edge at which the
  // record is taken (ref/timing.h rule 3; the empty slot that follows them holds no point and keeps nothing busy,
  // and the empty slots their bank reads left come before the last of them).
  const Job& last = jobs.back();
  uint64_t drain = 0;
  if (last.mode == Mode::First && future_.back().records == 2) {
    const JobSlots slots = runner_.job_slots(last);
    const uint64_t f = slots.slot_of(batch_[last_first].point);
    const uint64_t behind = std::min(slots.groups - 1 - f + bank.back().window, uint64_t(pipeline_slots(cfg_)) - 1);
    drain = behind > 0 ? behind - 1 : 0;
  }
  idle_ = edge + 1 + drain;
}

void TlmTarget::publish_next() {
  const Future& f = future_[future_head_++];
  publish_queued(f.records, f.counts);
}

void TlmTarget::advance_to(sc_time t) {
  while (busy() && edge_time(future_[future_head_].edge) <= t) publish_next();
}

sc_time TlmTarget::await_results(size_t n, sc_time t) {
  advance_to(t);
  sc_time when = t;
  while (readable() < n && busy()) {
    when = std::max(when, edge_time(future_[future_head_].edge));
    publish_next();
  }
  return when;
}

}  // namespace voxcd::sysc
