#include "ref/fixed.h"

#include <cmath>
#include <cstring>
#include <sstream>

namespace voxcd {

double FixedFormat::min_value() const { return std::ldexp(double(min_raw()), -frac); }
double FixedFormat::max_value() const { return std::ldexp(double(max_raw()), -frac); }
double FixedFormat::ulp() const { return std::ldexp(1.0, -frac); }

std::string FixedFormat::to_string() const {
  std::ostringstream s;
  s.precision(17);
  s << "signed " << width << "-bit with " << frac << " fraction bits, range [" << min_value() << ", "
    << max_value() << "]";
  return s.str();
}

bool fits_signed(int64_t v, int width) {
  if (width >= 64) return true;
  const int64_t lim = int64_t{1} << (width - 1);  // width <= 63: representable
  return v >= -lim && v < lim;
}

bool fits_unsigned(uint64_t v, int width) { return width >= 64 || v < (uint64_t{1} << width); }

int64_t quantize(double v, FixedFormat f, const std::string& what) {
  int64_t r = 0;
  if (try_quantize(v, f, &r)) return r;
  std::ostringstream s;
  s.precision(17);
  s << what << " = " << v << (std::isfinite(v) ? " does not fit " : " is not a finite number; format is ")
    << f.to_string();
  throw RangeError(s.str());
}

namespace {
// 2^e as a double, built from its exponent bits (std::ldexp is a library call, and this runs per pose entry).
double pow2(int e) {
  if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
  const uint64_t bits = uint64_t(e + 1023) << 52;
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
}  // namespace

bool try_quantize(double v, FixedFormat f, int64_t* out) {
  if (!std::isfinite(v)) return false;
  // Scaling by a power of two is exact (a product with 2^frac rounds like ldexp where the result is subnormal);
  // std::round rounds half away from zero. Both limits are powers of two, so the comparison in double is exact
  // too, and it comes before the conversion.
  const double scaled = std::round(v * pow2(f.frac));
  const double limit = pow2(f.width - 1);
  if (!(scaled >= -limit && scaled < limit)) return false;
  *out = static_cast<int64_t>(scaled);
  return true;
}

double to_double(int64_t raw, int frac) { return std::ldexp(double(raw), -frac); }

}  // namespace voxcd
