// RtlTarget: the Verilated RTL (rtl/voxcd_device.sv, --sc) behind the device's TLM-2.0 socket. A clocked method
// (the only writer of the model's input pins) writes memories through the write ports, feeds launched jobs back
// to back and takes every output record (an always-ready consumer), as host/device/rtl.cpp does in C++.
//
// b_transport waits: it first waits out its annotated delay (the pins must be driven at the transaction's time),
// then until the clocked method has done the access (a memory write, or the records a result read asks for).
// The time passes in the kernel, not in the annotation: an RTL needs its clock edges to happen, and waiting is
// what lets other processes run meanwhile. The loosely-timed TlmTarget annotates the same times without waiting.
#pragma once

#include <memory>
#include <string>

#include "voxcd/sysc/clocked_target.h"

class VerilatedFstSc;

namespace voxcd::sysc {

struct RtlPins;   // one signal per pin of the model
struct RtlModel;  // the Verilated model of one lane count

// Lane counts this build has SystemC RTL models of the 2-bit device (default widths) for.
std::vector<int> rtl_target_lanes();
// Every configuration this build has a SystemC RTL model for: the 2-bit device's lane counts, then the distance
// devices, the devices with shared voxmap banks, those with a deeper pipeline and the sparse devices
// (sysc/CMakeLists.txt, VOXCD_SYSC_DIST_MODELS, VOXCD_SYSC_BANKED_MODELS, VOXCD_SYSC_DEPTH_MODELS,
// VOXCD_SYSC_SPARSE_MODELS).
std::vector<DeviceConfig> rtl_target_configs();

class RtlTarget final : public ClockedTarget {
 public:
  // cfg must be one of rtl_target_configs(); trace_path "" = no waveform.
  RtlTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
            sc_core::sc_time access_latency = sc_core::SC_ZERO_TIME, const std::string& trace_path = "");
  ~RtlTarget() override;

  // Test-only fault injection (tests/sysc): memory writes start without waiting for the device to be idle, so a
  // write while a batch runs makes the RTL's assertion fail and the target fault. The platform never calls it.
  void start_writes_while_busy() { writes_wait_for_idle_ = false; }

 private:
  void start_of_simulation() override;

  void on_edge() override;
  void take_records();
  void drive_inputs();
  void drive_job(const Job& j);
  void drive_word(const MemRequest& req);

  std::string trace_path_;
  std::unique_ptr<RtlPins> pins_;
  std::unique_ptr<RtlModel> model_;
  std::unique_ptr<VerilatedFstSc> trace_;
  bool writes_wait_for_idle_ = true;
  uint64_t conflicts_seen_ = 0;  // the device's conflicts_o at the previous completion record
};

}  // namespace voxcd::sysc
