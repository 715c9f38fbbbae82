// A testing aid: the hook through which the project's tests plant a difference in a device, so that tests of
// `voxcd regress` and `voxcd conform` can check how a failure is reported and reproduced. Empty in the shipped library
// and tool, which read no environment variable for it: only the test build's tool (build/voxcd_testing,
// tests/testing/) sets it. Not part of the public API; docs/regress.md, "Testing aids".
#pragma once

#include <memory>
#include <string>

#include "voxcd/host/device/device.h"

namespace voxcd {

// Wraps (or returns) every device make_device makes for `backend`.
using DeviceTestingHook = std::unique_ptr<Device> (*)(std::unique_ptr<Device> dev, const std::string& backend);

// Sets the hook (nullptr: none, the default). Set it before any device is made; it is not synchronised.
void set_device_testing_hook(DeviceTestingHook hook);

}  // namespace voxcd
