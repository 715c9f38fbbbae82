#include "ref/fixed.h"

#include <cmath>
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
  auto fail = [&](const std::string& why) {
    std::ostringstream s;
    s.precision(17);
    s << what << " = " << v << " " << why << " " << f.to_string();
    throw RangeError(s.str());
  };
  if (!std::isfinite(v)) fail("is not a finite number; format is");
  // Scaling by a power of two is exact; std::round rounds half away from zero.
  const double scaled = std::round(std::ldexp(v, f.frac));
  // Compare in double before converting: both limits are powers of two (exact), so this is exact too.
  const double lo = -std::ldexp(1.0, f.width - 1);
  const double hi = std::ldexp(1.0, f.width - 1);
  if (!(scaled >= lo && scaled < hi)) fail("does not fit");
  return static_cast<int64_t>(scaled);
}

double to_double(int64_t raw, int frac) { return std::ldexp(double(raw), -frac); }

}  // namespace voxcd
