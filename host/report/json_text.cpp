#include "voxcd/host/report/json_text.h"

#include <cmath>
#include <cstdint>
#include <sstream>

namespace voxcd::report {

namespace {

// A floating-point number: at `digits` as a stream prints it, or (0) in its shortest exact form, a whole number as
// the tool always printed it, without ".0".
std::string float_text(const Json& j, int digits) {
  const double v = j.get<double>();
  if (digits > 0) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    return s.str();
  }
  if (v == std::trunc(v) && std::abs(v) < 1e15) return std::to_string(int64_t(v));
  return j.dump();
}

}  // namespace

std::string json_text(const Json& j, bool multiline, int float_digits) {
  const char* sep = multiline ? ",\n  " : ", ";
  if (j.is_object()) {
    std::string out = multiline ? "{\n  " : "{";
    bool first = true;
    for (const auto& [key, value] : j.items()) {
      out += (first ? "" : sep) + json_string(key) + ": " + json_text(value, false, float_digits);
      first = false;
    }
    return out + (multiline ? "\n}" : "}");
  }
  if (j.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + json_text(j[i], false, float_digits);
    return out + "]";
  }
  if (j.is_number_float()) return float_text(j, float_digits);
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string json_string(const std::string& s) { return json_text(Json(s)); }

}  // namespace voxcd::report
