// AxiRtlTarget: the Verilated AXI top (rtl/voxcd_axi.sv, --sc; AXI4-Lite and both streams 64 bits wide) behind
// the device's TLM-2.0 socket. A clocked method (the only writer of the model's input pins) is the AXI4-Lite master
// that writes the memories word by word and RUN, the AXI4-Stream master of the descriptors (16 beats each) and the
// always-ready slave of the records (4 beats each), which it decodes with the address map's own functions.
//
// Time as in RtlTarget (rtl_target.h), with the AXI top's costs in it: a memory word takes its AXI4-Lite writes
// (three edges each: address and data, response, the next request) instead of one edge, and a job its 16
// descriptor beats before the device sees it; the completion's cycles are the device's, as the top forwards them.
#pragma once

#include <memory>
#include <string>

#include "voxcd/sysc/clocked_target.h"

namespace voxcd::sysc {

struct AxiPins;   // one signal per pin of the model
struct AxiModel;  // the Verilated AXI top

// The configuration this build has a SystemC model of the AXI top for.
DeviceConfig axi_target_config();

class AxiRtlTarget final : public ClockedTarget {
 public:
  // cfg must be axi_target_config().
  AxiRtlTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
               sc_core::sc_time access_latency = sc_core::SC_ZERO_TIME);
  ~AxiRtlTarget() override;

  // AXI4-Lite writes the target made (a response other than OKAY faults the target).
  uint64_t lite_writes() const { return lite_writes_; }

 private:
  void on_edge() override;
  // What this edge did on each interface: the AXI4-Lite write response, the descriptor beat taken, the record beat.
  void take_lite_response();
  void take_job_beat();
  void take_record_beat();
  // The inputs for the next edge: the next AXI4-Lite write, the next descriptor beat.
  void drive_lite();
  void drive_job();
  // The next AXI4-Lite write for the memory request or RUN; false when there is none to make now.
  bool next_lite_write(uint32_t& addr, uint64_t& data);

  std::unique_ptr<AxiPins> pins_;
  std::unique_ptr<AxiModel> model_;

  bool run_written_ = false;  // RUN has opened the job stream
  bool run_pending_ = false;  // the RUN write is in flight
  // AXI4-Lite master: the write in flight (address and data channels, then the response), and the writes of the
  // current memory word done (a shell word takes two).
  bool lite_busy_ = false, aw_valid_ = false, w_valid_ = false, lite_is_mem_ = false;
  int part_ = 0;
  uint64_t lite_writes_ = 0;
  // Job stream: beat beat_ of the running batch's descriptor fed_.
  int beat_ = 0;
  uint8_t desc_[kJobBytes] = {};
  // Record stream: the beats of the record being received.
  uint8_t rec_[kRecordBytes] = {};
  int rec_beat_ = 0;
};

}  // namespace voxcd::sysc
