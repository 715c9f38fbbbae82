// The `rtl` backend: the Verilated device (rtl/voxcd_device.sv) driven through its pins, cycle by cycle. Not part
// of the public API: make_device("rtl", ...) returns it.
#pragma once

#include <memory>
#include <vector>

#include "host/device.h"

namespace voxcd {

// Lane counts this build has RTL models for (empty when it has none).
std::vector<int> rtl_lanes();
// Configurations beyond the default widths that this build has RTL models for (VOXCD_RTL_CONFIGS).
std::vector<DeviceConfig> rtl_configs();
// Throws DeviceError when there is no model for cfg (its lane count or widths), naming what there is.
std::unique_ptr<Device> make_rtl_device(const DeviceConfig& cfg, const DeviceOptions& opt);

}  // namespace voxcd
