// The `cpu` backend: the device contract computed fast on the host, bit-exact with ref/. Not part of the public
// API: make_device("cpu", ...) returns it.
#pragma once

#include <memory>

#include "voxcd/host/device/device.h"

namespace voxcd {

std::unique_ptr<Device> make_cpu_device(const DeviceConfig& cfg, const DeviceOptions& opt);

}  // namespace voxcd
