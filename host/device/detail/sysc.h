// The `sysc-rtl` and `sysc-tlm` backends: the SystemC example platform (sysc/), run in a child process per Device
// (voxcd_sysc_server) because SystemC elaborates once per process. Not part of the public API: make_device makes
// them.
#pragma once

#include <memory>
#include <string>

#include "voxcd/host/device/device.h"

namespace voxcd {

// Why the sysc backends cannot run here (the build has no device models, or its SystemC platform server is not
// built), with the command that builds it; "" when they can (or VOXCD_SYSC_SERVER names a server to try).
std::string sysc_unavailable();
// True when the sysc backends can run here: sysc_unavailable() is empty.
bool have_sysc();
// target: "rtl" or "tlm". Throws DeviceError when the server cannot be started or refuses cfg.
std::unique_ptr<Device> make_sysc_device(const std::string& target, const DeviceConfig& cfg, const DeviceOptions& opt);

// Simulated and wall time of a sysc device's last run (zero for other devices).
struct SyscRunTime {
  double simulated_s = 0;  // simulated time of the batch (staging, launch and read-out included)
  double wall_s = 0;       // wall time the server spent simulating it (no process-to-process traffic)
};
SyscRunTime sysc_last_run(const Device& dev);

}  // namespace voxcd
