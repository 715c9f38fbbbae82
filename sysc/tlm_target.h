// TlmTarget: the device as a loosely-timed TLM-2.0 model: results from ref/fast/fast.h's FastRunner (bit-exact with
// ref/pipeline.h, the specification), time from ref/timing.h (cycle-exact). b_transport never waits: it computes
// when the access would be done on the RTL target and annotates the delay. Assumes its initiators' transactions
// come in time order (one initiator, or initiators kept in order by their quantum).
#pragma once

#include <vector>

#include "voxcd/ref/fast/fast.h"
#include "voxcd/sysc/target.h"

namespace voxcd::sysc {

class TlmTarget final : public DeviceTarget {
 public:
  // `threads`: host threads computing a batch (FastRunner's; 1 = the simulation's own thread). Neither results nor
  // annotated times depend on it.
  TlmTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
            sc_core::sc_time access_latency = sc_core::SC_ZERO_TIME, unsigned threads = 1);

 private:
  sc_core::sc_time start(sc_core::sc_time& delay) override;
  sc_core::sc_time write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_core::sc_time t) override;
  sc_core::sc_time write_map(uint64_t first, const std::vector<uint64_t>& words, sc_core::sc_time t) override;
  void launch(std::vector<Job>& jobs, sc_core::sc_time t) override;
  void advance_to(sc_core::sc_time t) override;
  sc_core::sc_time await_results(size_t n, sc_core::sc_time t) override;
  bool busy() const override { return future_head_ < future_.size(); }
  sc_core::sc_time memory_write(uint64_t words, sc_core::sc_time t);
  void publish_next();

  // A launched job whose records are queued (DeviceTarget::queue_records) and not yet readable.
  struct Future {
    uint64_t edge;     // the edge at which the job's completion record is taken
    size_t records;    // the job's hits and its completion record
    JobCounts counts;  // what its completion record adds to the counters
  };
  FastRunner runner_;
  std::vector<Record> batch_;  // the records of the batch being launched (kept for its capacity)
  std::vector<Future> future_;  // launched jobs from future_head_ on are not readable yet
  size_t future_head_ = 0;
  uint64_t batch_free_ = 1;  // first edge at which a new batch may be presented
  uint64_t idle_ = 1;        // first edge at which the device is idle (memory writes may start)
};

}  // namespace voxcd::sysc
