// Fixed-point formats and quantisation from double: round to nearest, ties away from zero; a value that does
// not fit is an error, never a wrap or a clamp.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "voxcd/ref/error.h"

namespace voxcd {

// A signed two's complement format of `width` bits, `frac` of them below the binary point.
struct FixedFormat {
  int width;
  int frac;
  int64_t max_raw() const { return int64_t((uint64_t{1} << (width - 1)) - 1); }
  int64_t min_raw() const { return -max_raw() - 1; }
  double min_value() const;
  double max_value() const;
  double ulp() const;
  std::string to_string() const;  // "signed 18-bit with 16 fraction bits, [-2, 1.99998]"
};

// True when v is representable as a signed `width`-bit integer.
inline bool fits_signed(int64_t v, int width) {
  if (width >= 64) return true;
  const int64_t lim = int64_t{1} << (width - 1);  // width <= 63: representable
  return v >= -lim && v < lim;
}
// True when v is representable as an unsigned `width`-bit integer.
bool fits_unsigned(uint64_t v, int width);

// round(v * 2^frac), ties away from zero. Throws RangeError naming `what`, the value and the format when v is
// NaN, infinite, or outside the format's range after rounding.
int64_t quantize(double v, FixedFormat f, const std::string& what);

namespace detail {
// 2^e as a double, built from its exponent bits (std::ldexp is a library call, and this runs per pose entry).
inline double pow2(int e) {
  if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
  const uint64_t bits = uint64_t(e + 1023) << 52;
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
}  // namespace detail

// The same without the error: false (and *out untouched) when v is not finite or does not fit. For hot paths that
// build the error message only when it is needed (inline: it runs for every entry of every pose).
inline bool try_quantize(double v, FixedFormat f, int64_t* out) {
  if (!std::isfinite(v)) return false;
  // Scaling by a power of two is exact (a product with 2^frac rounds like ldexp where the result is subnormal);
  // std::round rounds half away from zero. Both limits are powers of two, so the comparison in double is exact
  // too, and it comes before the conversion.
  const double scaled = std::round(v * detail::pow2(f.frac));
  const double limit = detail::pow2(f.width - 1);
  if (!(scaled >= -limit && scaled < limit)) return false;
  *out = static_cast<int64_t>(scaled);
  return true;
}

// The real value of a raw fixed-point word.
double to_double(int64_t raw, int frac);

}  // namespace voxcd
