// Fixed-point formats and quantisation from double: round to nearest, ties away from zero; a value that does
// not fit is an error, never a wrap or a clamp.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace voxcd {

// Thrown when a value does not fit its fixed-point format (or is not a finite number).
struct RangeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

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
bool fits_signed(int64_t v, int width);
// True when v is representable as an unsigned `width`-bit integer.
bool fits_unsigned(uint64_t v, int width);

// round(v * 2^frac), ties away from zero. Throws RangeError naming `what`, the value and the format when v is
// NaN, infinite, or outside the format's range after rounding.
int64_t quantize(double v, FixedFormat f, const std::string& what);

// The same without the error: false (and *out untouched) when v is not finite or does not fit. For hot paths that
// build the error message only when it is needed.
bool try_quantize(double v, FixedFormat f, int64_t* out);

// The real value of a raw fixed-point word.
double to_double(int64_t raw, int frac);

}  // namespace voxcd
