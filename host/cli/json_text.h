// JSON as the tool prints it: values are nlohmann::ordered_json (keys in the order given); the text puts ", " and
// ": " between items, numbers in their shortest exact form (whole numbers without ".0"), strings escaped by nlohmann.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace voxcd::cli {

using Json = nlohmann::ordered_json;

// j on one line; with `multiline`, an object's keys one a line, indented by two spaces (its values on one line each).
std::string json_text(const Json& j, bool multiline = false);

// A string as a JSON string (quoted and escaped; bytes that are not UTF-8 become U+FFFD).
std::string json_string(const std::string& s);

}  // namespace voxcd::cli
