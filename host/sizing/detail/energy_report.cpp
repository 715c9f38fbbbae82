#include "voxcd/host/sizing/detail/energy_report.h"

#include <cmath>

#include "voxcd/host/sizing/digits.h"

namespace voxcd::detail {

namespace {
// What the frame's lookups are, as the reports name them.
constexpr const char* kLookupsOf = "mean frame";
}  // namespace

std::string si_text(double v, const std::string& unit) {
  static const char* const kPrefixes[] = {"p", "n", "u", "m", ""};
  if (v == 0 || !std::isfinite(v)) return digits_text(v, 4) + " " + unit;
  int k = 0;
  double scaled = v * 1e12;
  while (k < 4 && std::fabs(scaled) >= 1000) scaled /= 1000, ++k;
  return digits_text(scaled, 4) + " " + kPrefixes[k] + unit;
}

void energy_lines(std::ostream& o, const SizeReport& r) {
  const LookupEnergy& e = r.energy;
  o << "energy          " << si_text(r.frame_energy_j(), "J") << " a frame (the " << kLookupsOf << "'s "
    << digits_text(r.chosen().lookups, 6) << " lookups x " << digits_text(e.pj, 6) << " pJ a lookup at 0.18 um; "
    << e.source << ")\n";
  o << "power           " << si_text(r.power_w(), "W") << " at " << digits_text(r.rate, 8)
    << " frames/s (a frame's energy x the requested rate; the cycles between frames are not counted)\n";
  o << "projection      " << si_text(r.frame_energy_7nm_j(), "J") << " a frame, " << si_text(r.power_7nm_w(), "W")
    << " at 7 nm (" << digits_text(e.pj_7nm, 4)
    << " pJ a lookup: a projection of the 0.18 um figure by Stillmaker and Baas 2017, not measured)\n";
}

void add_energy_json(nlohmann::ordered_json& j, const SizeReport& r) {
  j["energy_lookups_per_frame"] = r.chosen().lookups;
  j["energy_lookups_of"] = kLookupsOf;
  j["energy_pj_per_lookup"] = r.energy.pj;
  j["energy_estimate"] = r.energy.estimate;
  j["energy_source"] = r.energy.source;
  j["energy_per_frame_j"] = r.frame_energy_j();
  j["power_w"] = r.power_w();
  j["energy_pj_per_lookup_7nm"] = r.energy.pj_7nm;
  j["energy_per_frame_7nm_j"] = r.frame_energy_7nm_j();
  j["power_7nm_w"] = r.power_7nm_w();
}

}  // namespace voxcd::detail
