#include "voxcd/host/cli/json_text.h"

#include <cmath>
#include <cstdint>

namespace voxcd::cli {

std::string json_text(const Json& j, bool multiline) {
  const char* sep = multiline ? ",\n  " : ", ";
  if (j.is_object()) {
    std::string out = multiline ? "{\n  " : "{";
    bool first = true;
    for (const auto& [key, value] : j.items()) {
      out += (first ? "" : sep) + json_string(key) + ": " + json_text(value);
      first = false;
    }
    return out + (multiline ? "\n}" : "}");
  }
  if (j.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + json_text(j[i]);
    return out + "]";
  }
  // A whole number held as a double prints as the tool always printed it, without ".0".
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (v == std::trunc(v) && std::abs(v) < 1e15) return std::to_string(int64_t(v));
  }
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string json_string(const std::string& s) { return json_text(Json(s)); }

}  // namespace voxcd::cli
