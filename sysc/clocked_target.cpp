#include "voxcd/sysc/clocked_target.h"

#include <verilated.h>

namespace voxcd::sysc {

using namespace sc_core;

ClockedTarget::ClockedTarget(sc_module_name name, const DeviceConfig& cfg, sc_time clock_period,
                             sc_time access_latency)
    : DeviceTarget(name, cfg, clock_period, access_latency),
      ctx_(std::make_unique<VerilatedContext>()),
      // Rising edges at T, 2T, ...: the first one resets the device.
      clk_("clk", clock_period, 0.5, clock_period, true) {
  ctx_->fatalOnError(false);  // a failed assertion faults the target instead of ending the process
  // A SystemC model takes the calling thread's context: make it this target's own.
  Verilated::threadContextp(ctx_.get());
}

ClockedTarget::~ClockedTarget() = default;

void ClockedTarget::start_clocked_method() {
  SC_METHOD(on_edge);
  sensitive << clk_.posedge_event();
  dont_initialize();
}

sc_time ClockedTarget::start(sc_time& delay) {
  // The pins live in the kernel's time: catch up with the initiator's local time first.
  wait(delay);
  delay = SC_ZERO_TIME;
  return sc_time_stamp();
}

sc_time ClockedTarget::write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_time t) {
  MemRequest req{t, true, first, words, {}};
  return write_memory(req);
}

sc_time ClockedTarget::write_map(uint64_t first, const std::vector<uint64_t>& words, sc_time t) {
  MemRequest req{t, false, first, {}, words};
  return write_memory(req);
}

sc_time ClockedTarget::write_memory(MemRequest& req) {
  mem_ = &req;
  while (!req.done && !fault_) wait(mem_event_);
  mem_ = nullptr;
  return sc_time_stamp();
}

void ClockedTarget::launch(std::vector<Job>& jobs, sc_time t) { batches_.push_back({t, std::move(jobs)}); }

void ClockedTarget::advance_to(sc_time t) {
  // Records taken at an edge at or before t are readable at t, whether or not the clocked method has run yet.
  while (edge_ < edge_at_or_before(t) && !fault_) wait(edge_event_);
}

sc_time ClockedTarget::await_results(size_t n, sc_time t) {
  advance_to(t);
  while (readable() < n && busy() && !fault_) wait(results_event_);
  return sc_time_stamp();
}

void ClockedTarget::word_written() {
  if (++mem_->written < mem_->size()) return;
  mem_->done = true;
  mem_event_.notify(SC_ZERO_TIME);
  mem_ = nullptr;
}

void ClockedTarget::job_done(uint64_t conflicts) {
  publish(partial_, conflicts);
  partial_.clear();
  results_event_.notify(SC_ZERO_TIME);
  if (++completed_ == batches_.front().jobs.size()) {
    batches_.pop_front();
    running_ = false;
  }
}

void ClockedTarget::start_memory_write(bool idle) {
  if (mem_ && !mem_->started && mem_->time < sc_time_stamp() && idle) mem_->started = true;
}

bool ClockedTarget::start_batch(bool writing) {
  if (running_ || writing || batches_.empty() || !(batches_.front().time < sc_time_stamp())) return false;
  running_ = true;
  fed_ = 0;
  completed_ = 0;
  return true;
}

void ClockedTarget::end_edge() {
  if (ctx_->gotError()) fault_ = true;
  if (fault_) {
    results_event_.notify(SC_ZERO_TIME);
    mem_event_.notify(SC_ZERO_TIME);
  }
  edge_event_.notify(SC_ZERO_TIME);
}

}  // namespace voxcd::sysc
