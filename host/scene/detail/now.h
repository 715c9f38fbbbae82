// The stepper's clock: seconds on the steady clock, for the frame's per-stage times.
#pragma once

#include <chrono>

namespace voxcd::detail {

inline double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace voxcd::detail
