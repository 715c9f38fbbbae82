// A configuration's pipeline depth (the register stages the lanes add, the RTL's Depth, ref/'s DeviceConfig::depth),
// read and set whether or not this build's DeviceConfig has that member: without it every device has the one
// datapath of depth 0, and asking for another depth is a ConfigError. So the sizing steps loop over the depths the
// device offers, whichever device the build has.
#pragma once

#include <string>

#include "voxcd/ref/config.h"

namespace voxcd::detail {

template <class C>
auto depth_member(const C& c, int) -> decltype(int(c.depth)) {
  return int(c.depth);
}
template <class C>
int depth_member(const C&, long) {
  return 0;
}
template <class C>
auto set_depth_member(C& c, int d, int) -> decltype(c.depth = d, bool()) {
  c.depth = d;
  return true;
}
template <class C>
bool set_depth_member(C&, int d, long) {
  return d == 0;
}

// cfg's depth (0 when DeviceConfig has none).
inline int config_depth(const DeviceConfig& cfg) { return depth_member(cfg, 0); }

// cfg at depth d, validated: ConfigError when d is negative or deeper than the device's deepest.
inline DeviceConfig with_depth(DeviceConfig cfg, int d) {
  if (d < 0 || !set_depth_member(cfg, d, 0))
    throw ConfigError("depth " + std::to_string(d) + ": this device has depth 0 only (its datapath has no "
                      "added register stages)");
  cfg.validate();
  return cfg;
}

}  // namespace voxcd::detail
