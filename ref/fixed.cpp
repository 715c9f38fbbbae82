#include "voxcd/ref/fixed.h"

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

double to_double(int64_t raw, int frac) { return std::ldexp(double(raw), -frac); }

}  // namespace voxcd
