// The lane counts the build has RTL models of at the default widths (VOXCD_RTL_LANES, docs/build.md): tests that
// need a particular lane count take the nearest one the build has.
#pragma once

#include <algorithm>
#include <vector>

#include "voxcd/host/device/detail/rtl.h"

namespace voxcd {

// `want` when the build has a model for it, else the first lane count it has.
inline int built_rtl_lanes(int want) {
  const std::vector<int> l = rtl_lanes();
  return l.empty() || std::find(l.begin(), l.end(), want) != l.end() ? want : l.front();
}

}  // namespace voxcd
