// Numbers as the sizing reports print them.
#pragma once

#include <sstream>
#include <string>

namespace voxcd::detail {

// v with `digits` significant digits in the stream's default float format ("0.01086", "1.02564e+06").
inline std::string digits_text(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace voxcd::detail
