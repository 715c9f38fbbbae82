// Devices (public: <voxcd/voxcd.h>): the backends by name (device/device.h: device_backends, make_device), their
// configuration (ref/config.h), conformance vectors run on them (device/conform.h), and the smallest device for a
// scene (size_device, as `voxcd size` derives it: docs/size.md).
#pragma once

#include <cstdint>
#include <string>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/device/conform.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/sizing/size_options.h"  // SizeOptions: what is asked of the device
#include "voxcd/ref/config.h"

namespace voxcd {

struct DeviceSize {
  DeviceConfig config;  // the smallest device that meets the request
  double error = 0;     // its fixed-point path's worst error, world units
  double frame_rate = 0;  // the frame rate its largest frame allows at the clock (0: no frame needed the device)
  std::string text;     // the report of `voxcd size SCENE`
  std::string json;     // the report of `voxcd size SCENE --json`
};

// The smallest device for the scene file `scene_file` (docs/scenes.md). SizeError when the request cannot be met,
// SceneFileError for the file, MeshError for a type's mesh; OptionError "clock_mhz: ..." for a clock that is not a
// positive number.
DeviceSize size_device(const std::string& scene_file, const SizeOptions& options = {});

}  // namespace voxcd
