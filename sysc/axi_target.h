// AxiRtlTarget: the Verilated AXI top (rtl/voxcd_axi.sv, --sc; AXI4-Lite and both streams 64 bits wide) behind
// the device's TLM-2.0 socket. A clocked method (the only writer of the model's input pins) is the AXI4-Lite master
// that writes the memories word by word and RUN, the AXI4-Stream master of the descriptors (16 beats each) and the
// always-ready slave of the records (4 beats each), which it decodes with the address map's own functions.
//
// Time as in RtlTarget (rtl_target.h), with the AXI top's costs in it: a memory word takes its AXI4-Lite writes
// (three edges each: address and data, response, the next request) instead of one edge, and a job its 16
// descriptor beats before the device sees it; the completion's cycles are the device's, as the top forwards them.
#pragma once

#include <deque>
#include <memory>
#include <string>

#include "voxcd/sysc/target.h"

class VerilatedContext;

namespace voxcd::sysc {

struct AxiPins;   // one signal per pin of the model
struct AxiModel;  // the Verilated AXI top

// The configuration this build has a SystemC model of the AXI top for.
DeviceConfig axi_target_config();

class AxiRtlTarget final : public DeviceTarget {
 public:
  SC_HAS_PROCESS(AxiRtlTarget);
  // cfg must be axi_target_config().
  AxiRtlTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
               sc_core::sc_time access_latency = sc_core::SC_ZERO_TIME);
  ~AxiRtlTarget() override;

  uint64_t edges() const { return edge_; }
  // AXI4-Lite writes the target made (a response other than OKAY faults the target).
  uint64_t lite_writes() const { return lite_writes_; }

 private:
  struct MemRequest {
    sc_core::sc_time time;
    bool shell = true;
    uint64_t first = 0;
    std::vector<ShellWord> shell_words;
    std::vector<uint64_t> map_words;
    size_t size() const { return shell ? shell_words.size() : map_words.size(); }
    bool started = false;
    size_t written = 0;  // whole words
    int part = 0;        // AXI4-Lite writes of the current word done
    bool done = false;
  };
  struct Batch {
    sc_core::sc_time time;
    std::vector<Job> jobs;
  };

  sc_core::sc_time start(sc_core::sc_time& delay) override;
  sc_core::sc_time write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_core::sc_time t) override;
  sc_core::sc_time write_map(uint64_t first, const std::vector<uint64_t>& words, sc_core::sc_time t) override;
  sc_core::sc_time write_memory(MemRequest& req);
  void launch(std::vector<Job>& jobs, sc_core::sc_time t) override;
  void advance_to(sc_core::sc_time t) override;
  sc_core::sc_time await_results(size_t n, sc_core::sc_time t) override;
  bool busy() const override { return running_ || !batches_.empty(); }
  bool faulted() const override { return fault_; }

  void on_edge();  // the clocked method
  // The next AXI4-Lite write for the memory request or RUN; false when there is none to make now.
  bool next_lite_write(uint32_t& addr, uint64_t& data);

  std::unique_ptr<VerilatedContext> ctx_;
  sc_core::sc_clock clk_;
  std::unique_ptr<AxiPins> pins_;
  std::unique_ptr<AxiModel> model_;

  sc_core::sc_event edge_event_, results_event_, mem_event_;
  uint64_t edge_ = 0;
  bool fault_ = false;
  MemRequest* mem_ = nullptr;
  std::deque<Batch> batches_;
  bool running_ = false;
  bool run_written_ = false;  // RUN has opened the job stream
  bool run_pending_ = false;  // the RUN write is in flight
  // AXI4-Lite master: the write in flight (address and data channels, then the response).
  bool lite_busy_ = false, aw_valid_ = false, w_valid_ = false, lite_is_mem_ = false;
  uint64_t lite_writes_ = 0;
  // Job stream: descriptor fed_ of the running batch, beat beat_ of it.
  bool job_valid_ = false;
  size_t fed_ = 0, completed_ = 0;
  int beat_ = 0;
  uint8_t desc_[kJobBytes] = {};
  // Record stream: the beats of the record being received.
  uint8_t rec_[kRecordBytes] = {};
  int rec_beat_ = 0;
  std::vector<Record> partial_;
};

}  // namespace voxcd::sysc
