// The energy part of `voxcd size`'s reports (docs/size.md, "Energy and power"): a frame's energy, the power at the
// requested rate, where the energy per lookup comes from (measured or an estimate), and the 7 nm projection.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "voxcd/host/sizing/size.h"

namespace voxcd::detail {

// v with an SI prefix and `unit`, four significant digits: "2.324 uJ", "23.24 mW", "0 W".
std::string si_text(double v, const std::string& unit);
// The text lines "energy", "power" and "projection".
void energy_lines(std::ostream& o, const SizeReport& r);
// The keys energy_* and power_* of the report's JSON object.
void add_energy_json(nlohmann::ordered_json& j, const SizeReport& r);

}  // namespace voxcd::detail
