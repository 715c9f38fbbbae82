// The lane counts the build has SystemC RTL models of (VOXCD_SYSC_LANES, docs/build.md): tests that need a
// particular lane count on the RTL target take the nearest one the build has.
#pragma once

#include <algorithm>
#include <vector>

#include "voxcd/sysc/rtl_target.h"

namespace voxcd::sysc {

// `want` when the build has a model for it, else the first lane count it has.
inline int built_lanes(int want) {
  const std::vector<int> l = rtl_target_lanes();
  return std::find(l.begin(), l.end(), want) != l.end() ? want : l.front();
}

}  // namespace voxcd::sysc
