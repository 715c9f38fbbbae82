// Numbered, named directed cases of the device contract with hand-derived expectations. Every backend runs
// them (tests/ref checks ref/ against the expectations; tests/rtl checks the RTL against ref/).
#pragma once

#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::testing {

struct DirectedCase {
  std::string name;  // "01_point_on_voxel_face"
  DeviceConfig config;
  DeviceMemory memory;
  std::vector<Job> jobs;
  std::vector<Record> expected;  // derived by hand, never by running ref/
};

const std::vector<DirectedCase>& directed_cases();

}  // namespace voxcd::testing
