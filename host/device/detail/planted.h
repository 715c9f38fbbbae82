// A testing aid: a planted difference, so that tests of `voxcd regress` and `voxcd conform` can check how a
// failure is reported and reproduced. Not part of the public API; docs/regress.md, "Testing aids".
#pragma once

#include <memory>
#include <string>

#include "voxcd/host/device/device.h"

namespace voxcd {

// The environment variable that plants the difference: "BACKEND:LANES:SEED".
inline constexpr const char* kPlantVariable = "VOXCD_TESTING_PLANT";

// `dev` itself when VOXCD_TESTING_PLANT is unset or names another backend or lane count; else `dev` wrapped so
// that, on the jobs `voxcd conform --generate --seed SEED` makes for its configuration, the first record of its
// stream differs (a hit's x plus one, or a done's hits plus one). DeviceError for a malformed variable.
std::unique_ptr<Device> plant_from_environment(std::unique_ptr<Device> dev, const std::string& backend);

}  // namespace voxcd
