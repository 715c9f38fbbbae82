// What is asked of a device sized for a scene (public: <voxcd/host/api/devices.h> includes it for size_device;
// sizing/size.h's SizeRequest is one, with what the tool adds). Here in sizing/, below the API, so that sizing uses
// nothing of api/.
#pragma once

#include <cstdint>

namespace voxcd {

// What is asked of the device; 0 (or unset) takes the scene file's value, or its default.
struct SizeOptions {
  double accuracy = 0;          // world units: the fixed-point path's worst error
  double contact_accuracy = 0;  // world units: how far outside the other surface a contact may lie
  double rate = 0;              // frames per second
  double clock_mhz = 0;         // the device clock of the rate
  uint64_t frames = 0;          // frames simulated to measure the scene
  bool cost = false;            // also synthesise the configuration with yosys (LUTs, FFs, DSPs, block RAMs)
};

}  // namespace voxcd
