// JSON as the tool prints it: values are nlohmann::ordered_json (keys in the order given); the text puts ", " and
// ": " between items, numbers in their shortest exact form (whole numbers without ".0"), strings escaped by nlohmann.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace voxcd::report {

using Json = nlohmann::ordered_json;

// j on one line; with `multiline`, an object's keys one a line, indented by two spaces (its values on one line each).
// With `float_digits` > 0, floating-point numbers are printed as a C++ stream prints them at that precision
// ("0.000425478", "1.02564e+06" at 6: simulate's summary) instead of their shortest exact form.
std::string json_text(const Json& j, bool multiline = false, int float_digits = 0);

// A string as a JSON string (quoted and escaped; bytes that are not UTF-8 become U+FFFD).
std::string json_string(const std::string& s);

}  // namespace voxcd::report
