// Platform: an example virtual platform: a host processor (HostCpu) bound to the device, the device being the
// Verilated RTL (RtlTarget), the Verilated AXI top (AxiRtlTarget) or the loosely-timed model (TlmTarget), chosen
// by one option. Nothing else in the platform knows which.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "voxcd/sysc/host_cpu.h"
#include "voxcd/sysc/target.h"

namespace voxcd::sysc {

enum class TargetKind { Rtl, Tlm, RtlAxi };
const char* target_name(TargetKind k);                          // "rtl", "tlm", "rtl-axi"
std::optional<TargetKind> parse_target(const std::string& s);  // "rtl", "tlm", "rtl-axi"

struct PlatformOptions {
  TargetKind target = TargetKind::Tlm;
  DeviceConfig config;
  sc_core::sc_time clock_period{10, sc_core::SC_NS};
  sc_core::sc_time access_latency = sc_core::SC_ZERO_TIME;  // added to every access of the device
  sc_core::sc_time quantum{1, sc_core::SC_US};              // the host's loosely-timed quantum
  size_t burst = 4096;                                      // bytes per transaction at most
  std::string trace_path;                                   // RTL target: FST waveform ("" = none)
};

class Platform : public sc_core::sc_module {
 public:
  Platform(sc_core::sc_module_name name, const PlatformOptions& opt);
  HostCpu cpu;
  DeviceTarget& target() { return *target_; }
  const PlatformOptions& options() const { return opt_; }

  // From sc_main (outside the simulation): runs `task` in the host's thread and simulates until it is done;
  // rethrows what it threw.
  void execute(HostCpu::Task task);

 private:
  PlatformOptions opt_;
  std::unique_ptr<DeviceTarget> target_;
};

// Simulates until every listed host has finished its posted tasks; rethrows the first error.
void run_until_idle(std::initializer_list<HostCpu*> hosts);

}  // namespace voxcd::sysc
