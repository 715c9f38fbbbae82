// The `rtl` backend: the Verilated device (rtl/voxcd_device.sv) driven through its pins, cycle by cycle. Not part
// of the public API: make_device("rtl", ...) returns it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "voxcd/host/device/device.h"

namespace voxcd {

// Why the rtl backend cannot run here (its models not configured, not built, or built from other sources), with
// the command that builds them; "" when it can. The models are loaded on first use (detail/rtl_module.h).
std::string rtl_unavailable();
// Lane counts this build has RTL models for (empty when it has none).
std::vector<int> rtl_lanes();
// Configurations beyond the default widths that this build has RTL models for (VOXCD_RTL_CONFIGS).
std::vector<DeviceConfig> rtl_configs();
// Distance devices (SB > 2) this build has RTL models for (VOXCD_RTL_DIST_MODELS).
std::vector<DeviceConfig> rtl_distance_configs();
// Devices with shared voxmap banks (BANKS > 0) this build has RTL models for (VOXCD_RTL_BANKED_MODELS).
std::vector<DeviceConfig> rtl_banked_configs();
// Devices with a deeper pipeline (DeviceConfig::depth > 0) this build has RTL models for (VOXCD_RTL_DEPTH_MODELS).
std::vector<DeviceConfig> rtl_depth_configs();
// Sparse devices (BL > 0) this build has RTL models for (VOXCD_RTL_SPARSE_MODELS).
std::vector<DeviceConfig> rtl_sparse_configs();
// Wide devices (16 to 64 lanes) this build has RTL models for (VOXCD_RTL_WIDE_MODELS; with VOXCD_RTL_WIDE on, the
// full-size ones of VOXCD_RTL_WIDE_FULL_MODELS too).
std::vector<DeviceConfig> rtl_wide_configs();
// Throws DeviceError when the models cannot be loaded (rtl_unavailable()) or have none for cfg (its lane count or
// widths), naming what there is.
std::unique_ptr<Device> make_rtl_device(const DeviceConfig& cfg, const DeviceOptions& opt);

// Test-only fault injection: the backend misbehaves on purpose so that tests can reach the checks that guard
// against a misbehaving device (tests/rtl/test_rtl_faults.cpp). make_device never sets any; with none set the
// backend is the one above.
struct RtlFaults {
  // Drive one voxmap write while the device is busy with a job: the RTL's assertion against it fails.
  bool write_while_busy = false;
  // Take one completion record fewer than there are jobs before the run ends, as a host that miscounted would:
  // the last job's records then come after what the run takes for the last completion.
  bool miss_last_completion = false;
};
std::unique_ptr<Device> make_rtl_device(const DeviceConfig& cfg, const DeviceOptions& opt, const RtlFaults& faults);

}  // namespace voxcd
