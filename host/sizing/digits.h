// Numbers as the sizing reports print them.
#pragma once

#include <cstdint>
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

// Bits as "448 kbit", "1.5 Mbit" or "512 bit" (binary prefixes, four significant digits).
inline std::string bits_text(uint64_t b) {
  if (b >= (uint64_t{1} << 20)) return digits_text(double(b) / double(uint64_t{1} << 20), 4) + " Mbit";
  if (b >= (uint64_t{1} << 10)) return digits_text(double(b) / 1024.0, 4) + " kbit";
  return std::to_string(b) + " bit";
}

}  // namespace voxcd::detail
