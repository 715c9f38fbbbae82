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
  int64_t r = 0;
  if (try_quantize(v, f, &r)) return r;
  std::ostringstream s;
  s.precision(17);
  s << what << " = " << v << (std::isfinite(v) ? " does not fit " : " is not a finite number; format is ")
    << f.to_string();
  throw RangeError(s.str());
}

bool try_quantize(double v, FixedFormat f, int64_t* out) {
  if (!std::isfinite(v)) return false;
  // Scaling by a power of two is exact; std::round rounds half away from zero. Both limits are powers of two, so
  // the comparison in double is exact too, and it comes before the conversion.
  const double scaled = std::round(std::ldexp(v, f.frac));
  if (!(scaled >= -std::ldexp(1.0, f.width - 1) && scaled < std::ldexp(1.0, f.width - 1))) return false;
  *out = static_cast<int64_t>(scaled);
  return true;
}

double to_double(int64_t raw, int frac) { return std::ldexp(double(raw), -frac); }

}  // namespace voxcd
