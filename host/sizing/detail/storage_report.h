// The "Sparse or dense" part of `voxcd size`'s reports (docs/size.md): which storage was taken and why, both
// layouts' memory (a type's table and bricks apart) and their memories' block RAMs.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "voxcd/host/sizing/size.h"

namespace voxcd::detail {

// The text lines, from "storage" on.
void storage_lines(std::ostream& o, const SizeReport& r);
// The JSON object of the key "storage".
nlohmann::ordered_json storage_json(const SizeReport& r);

}  // namespace voxcd::detail
